// ctest-labels: physics
// The 5-mass template model: mass matrix, inverse/forward dynamics consistency, free-flight invariants.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>

#include "model/template_model.hpp"
#include "model/template_params.hpp"

using namespace centaur::model;

namespace {

VectorQ randomConfiguration(std::mt19937& rng) {
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  VectorQ q;
  for (int i = 0; i < kTemplateNq; ++i) q[i] = 0.3 * U(rng);
  Eigen::Vector4d rho(1.0 + 0.2 * U(rng), 0.3 * U(rng), 0.3 * U(rng), 0.3 * U(rng));
  q.segment<4>(3) = rho.normalized();
  q[9] -= 0.6;  // feet below the waist
  return q;
}

VectorV randomVelocity(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  VectorV v;
  for (int i = 0; i < kTemplateNv; ++i) v[i] = scale * U(rng);
  return v;
}

// One RK4 step of the free (tau = 0, F = 0) template dynamics.
void rk4Free(const TemplateParams& P, VectorQ& q, VectorV& v, double h) {
  const Eigen::Matrix<double, 12, 1> tau = Eigen::Matrix<double, 12, 1>::Zero();
  const VectorF F = VectorF::Zero();
  auto f = [&](const VectorQ& qq, const VectorV& vv, VectorQ& dq, VectorV& dv) {
    dq = configurationRate(qq, vv);
    dv = forwardDynamics(P, qq, vv, tau, F);
  };
  VectorQ k1q, k2q, k3q, k4q;
  VectorV k1v, k2v, k3v, k4v;
  f(q, v, k1q, k1v);
  f(q + 0.5 * h * k1q, v + 0.5 * h * k1v, k2q, k2v);
  f(q + 0.5 * h * k2q, v + 0.5 * h * k2v, k3q, k3v);
  f(q + h * k3q, v + h * k3v, k4q, k4v);
  q += h / 6.0 * (k1q + 2 * k2q + 2 * k3q + k4q);
  v += h / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v);
  q.segment<4>(3).normalize();
}

}  // namespace

TEST(TemplateModel, MassMatrixIsSymmetricPositiveDefinite) {
  std::mt19937 rng(1);
  for (const auto& preset : templatePresetNames()) {
    const TemplateParams P = templatePreset(preset);
    for (int trial = 0; trial < 20; ++trial) {
      const MatrixV B = massMatrix(P, randomConfiguration(rng));
      EXPECT_LT((B - B.transpose()).cwiseAbs().maxCoeff(), 1e-12) << preset;
      EXPECT_GT(Eigen::SelfAdjointEigenSolver<MatrixV>(B).eigenvalues().minCoeff(), 1e-6) << preset;
      EXPECT_NEAR(B(0, 0), P.totalMass(), 1e-9);  // translation block is m I
    }
  }
}

TEST(TemplateModel, StaticStandingNeedsExactlyTheWeight) {
  // Level waist at rest, gravity only: the unactuated linear rows equal the total weight, and the
  // forces that cancel them reproduce m g.
  const TemplateParams P = templatePreset("centauro");
  VectorQ q = VectorQ::Zero();
  q[3] = 1.0;
  const VectorV h = nonlinearTerms(P, q, VectorV::Zero());
  EXPECT_NEAR(h[2], P.totalMass() * P.gravity, 1e-9);
  EXPECT_NEAR(h[0], 0.0, 1e-12);
  EXPECT_NEAR(h[1], 0.0, 1e-12);
  // Moment about the waist origin of the weights: (sum m_b r_b) x m g ... = m_total * c x g.
  const Eigen::Vector3d c = centerOfMass(P, q);
  const Eigen::Vector3d expected = (c - q.head<3>()).cross(Eigen::Vector3d(0, 0, P.totalMass() * P.gravity));
  EXPECT_LT((h.segment<3>(3) - expected).norm(), 1e-9);
}

TEST(TemplateModel, KineticEnergyEqualsBodySum) {
  std::mt19937 rng(2);
  const TemplateParams P = templatePreset("centauro");
  const VectorQ q = randomConfiguration(rng);
  const VectorV v = randomVelocity(rng, 1.0);
  const Eigen::Matrix3d R = quatToRotation(q.data() + 3);
  const Eigen::Vector3d om = v.segment<3>(3);
  const Eigen::Vector3d vw = v.head<3>() + om.cross(R * P.waist_com);
  double T = 0.5 * P.waist_mass * vw.squaredNorm() + 0.5 * om.dot(R * P.waist_inertia * R.transpose() * om);
  for (int i = 0; i < kNumFeet; ++i) {
    const Eigen::Vector3d vf = footJacobian(P, q, i) * v;
    T += 0.5 * P.foot_mass * vf.squaredNorm() + 0.5 * om.dot(R * P.foot_inertia * R.transpose() * om);
  }
  EXPECT_NEAR(kineticEnergy(P, q, v), T, 1e-10 * std::max(1.0, T));
}

TEST(TemplateModel, FreeFlightConservesMomentaAndEnergy) {
  // Ballistic flight with tau = 0: linear momentum changes by m g t, angular momentum about the CoM and the
  // total energy stay constant (RK4 at 1 ms over 1 s).
  std::mt19937 rng(3);
  for (const auto& preset : templatePresetNames()) {
    const TemplateParams P = templatePreset(preset);
    VectorQ q = randomConfiguration(rng);
    VectorV v = randomVelocity(rng, 1.5);
    const Eigen::Vector3d p0 = linearMomentum(P, q, v);
    const Eigen::Vector3d L0 = angularMomentumAboutCom(P, q, v);
    const double E0 = kineticEnergy(P, q, v) + potentialEnergy(P, q);
    const double h = 1e-3;
    for (int k = 0; k < 1000; ++k) rk4Free(P, q, v, h);
    const Eigen::Vector3d dp = linearMomentum(P, q, v) - p0;
    EXPECT_LT((dp - Eigen::Vector3d(0, 0, -P.totalMass() * P.gravity * 1.0)).norm(), 1e-6 * P.totalMass()) << preset;
    EXPECT_LT((angularMomentumAboutCom(P, q, v) - L0).norm(), 1e-6 * std::max(1.0, L0.norm())) << preset;
    const double E1 = kineticEnergy(P, q, v) + potentialEnergy(P, q);
    EXPECT_NEAR(E1, E0, 1e-6 * std::abs(E0)) << preset;
  }
}

TEST(TemplateModel, InverseDynamicsInvertsForwardDynamics) {
  std::mt19937 rng(4);
  const TemplateParams P = templatePreset("centauro-authors");
  const VectorQ q = randomConfiguration(rng);
  const VectorV v = randomVelocity(rng, 1.0);
  Eigen::Matrix<double, 12, 1> tau;
  VectorF F;
  for (int i = 0; i < 12; ++i) tau[i] = 100.0 * std::sin(i + 1.0), F[i] = 50.0 * std::cos(i + 2.0);
  const VectorV a = forwardDynamics(P, q, v, tau, F);
  VectorV tau_full;
  inverseDynamics(P, q.data(), v.data(), a.data(), F.data(), tau_full.data());
  EXPECT_LT(tau_full.head<6>().norm(), 1e-8);
  EXPECT_LT((tau_full.tail<12>() - tau).norm(), 1e-8);
}

TEST(TemplateModel, FootJacobianMatchesFiniteDifferences) {
  std::mt19937 rng(5);
  const TemplateParams P = templatePreset("centauro");
  const VectorQ q = randomConfiguration(rng);
  const VectorV v = randomVelocity(rng, 1.0);
  const double h = 1e-6;
  for (int i = 0; i < kNumFeet; ++i) {
    const Eigen::Vector3d analytic = footJacobian(P, q, i) * v;
    const VectorQ qp = q + h * configurationRate(q, v), qm = q - h * configurationRate(q, v);
    const Eigen::Vector3d fd = (footPosition(P, i, qp.data(), qp.data() + 3, qp.data() + 7 + 3 * i) -
                                footPosition(P, i, qm.data(), qm.data() + 3, qm.data() + 7 + 3 * i)) /
                               (2 * h);
    EXPECT_LT((analytic - fd).norm(), 1e-7);
  }
}
