// ctest-labels: unit physics
// The fixed-base arm chain (model/serial_chain.hpp, numbers from the MJCF) against the whole-robot RobotModel
// (MuJoCo) with the pelvis at the world origin and only the arm joints moving: end-effector point, inverse
// dynamics (M qdd + C qd + g rows of the arm) and angular momentum (moved from the robot CoM to the chain's
// point). Every arm element derivative (Jacobian, weighted Hessian) and the assembled NLP derivatives against
// central finite differences.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "model/chain_from_mjcf.hpp"
#include "model/robot_model.hpp"
#include "planner/arm_elements.hpp"
#include "planner/arm_flywheel_problem.hpp"
#include "planner/nlp_fd_check.hpp"

using namespace centaur;
using namespace centaur::planner;

namespace {

double relErr(double a, double b) { return std::abs(a - b) / std::max(1.0, std::max(std::abs(a), std::abs(b))); }

struct Fixture {
  model::SerialChain chain = model::chainFromMjcf(model::centauroMjcfPath(), model::centauroLeftArmSpec());
  RobotModel robot{model::centauroMjcfPath()};
  std::vector<int> cols;  // RobotModel velocity index of each arm joint
  Fixture() {
    for (const auto& L : chain.links) cols.push_back(6 + robot.jointIndex(L.joint));
  }
  // Robot configuration: pelvis at the origin (identity), every joint at home except the arm.
  void set(const Eigen::VectorXd& qa, const Eigen::VectorXd& qda) {
    Eigen::VectorXd q(robot.nq()), v = Eigen::VectorXd::Zero(robot.nv());
    q.setZero();
    q[3] = 1.0;
    q.tail(robot.numJoints()) = robot.homeJoints();
    for (int i = 0; i < 7; ++i) {
      q[7 + cols[i] - 6] = qa[i];
      v[cols[i]] = qda[i];
    }
    robot.update(q, v);
  }
  Eigen::VectorXd randomPosture(std::mt19937& rng) const {
    Eigen::VectorXd q(7);
    for (int i = 0; i < 7; ++i) {
      std::uniform_real_distribution<double> U(chain.links[i].q_min, chain.links[i].q_max);
      q[i] = U(rng);
    }
    return q;
  }
};

}  // namespace

TEST(ArmChain, DescriptionComesFromTheMjcf) {
  Fixture f;
  ASSERT_EQ(f.chain.dof(), 7);
  double m = 0.0;
  for (const auto& L : f.chain.links) m += L.mass;
  EXPECT_NEAR(m, 11.351, 2e-3);  // one arm with its ball hand (MODEL.md)
  EXPECT_NEAR(f.chain.links[0].q_min, -3.312, 1e-9);
  EXPECT_NEAR(f.chain.links[6].tau_max, 28.32, 1e-9);
  EXPECT_NEAR(f.chain.links[0].qd_max, 3.86, 1e-9);
  EXPECT_TRUE(f.chain.base_p.isApprox(Eigen::Vector3d(0.2, 0.0, 0.256), 1e-9));
  EXPECT_TRUE(f.chain.gravity.isApprox(Eigen::Vector3d(0, 0, -9.81), 1e-12));
  for (int i = 0; i < 7; ++i) {
    EXPECT_NEAR(f.chain.links[i].q_home, f.robot.homeJoints()[f.robot.jointIndex(f.chain.links[i].joint)], 1e-12);
  }
}

TEST(ArmChain, EndEffectorMatchesRobotModel) {
  Fixture f;
  std::mt19937 rng(3);
  const int site = f.robot.frameId("ball1_tip");
  const int wrist = f.robot.frameId("arm1_7");
  ASSERT_GE(site, 0);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd q = f.randomPosture(rng);
    f.set(q, Eigen::VectorXd::Zero(7));
    EXPECT_LT((model::chainEndEffector(f.chain, q.data()) - f.robot.framePose(site).translation()).norm(), 1e-10);
    EXPECT_LT((model::chainPoint(f.chain, q.data(), 6, Eigen::Vector3d::Zero()) - f.robot.framePose(wrist).translation())
                  .norm(),
              1e-10);
  }
}

TEST(ArmChain, InverseDynamicsMatchesRobotModelRows) {
  Fixture f;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(-3.0, 3.0);
  RowMatrixXd M(f.robot.nv(), f.robot.nv());
  Eigen::VectorXd b(f.robot.nv());
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd q = f.randomPosture(rng);
    Eigen::VectorXd qd(7), qdd(7), tau(7);
    for (int i = 0; i < 7; ++i) qd[i] = U(rng), qdd[i] = 5.0 * U(rng);
    f.set(q, qd);
    f.robot.massMatrix(M);
    f.robot.biasForces(b);
    model::chainInverseDynamics(f.chain, q.data(), qd.data(), qdd.data(), tau.data());
    for (int i = 0; i < 7; ++i) {
      double ref = b[f.cols[i]];
      for (int j = 0; j < 7; ++j) ref += M(f.cols[i], f.cols[j]) * qdd[j];  // base fixed: no base acceleration
      EXPECT_NEAR(tau[i], ref, 1e-9 * std::max(1.0, std::abs(ref))) << "joint " << i;
    }
  }
  // Static check: with qd = qdd = 0 the torques hold the arm against gravity; a horizontal arm loads the
  // shoulder far more than a hanging one.
  Eigen::VectorXd z = Eigen::VectorXd::Zero(7), hang = z, tau_h(7), tau_f(7);
  hang[1] = 0.3;
  model::chainInverseDynamics(f.chain, hang.data(), z.data(), z.data(), tau_h.data());
  Eigen::VectorXd fwd = hang;
  fwd[0] = -M_PI / 2;  // shoulder pitch: arm forward, horizontal
  model::chainInverseDynamics(f.chain, fwd.data(), z.data(), z.data(), tau_f.data());
  EXPECT_GT(std::abs(tau_f[0]), 10.0 * std::abs(tau_h[0]));
}

TEST(ArmChain, AngularMomentumMatchesRobotModelCentroidalMomentum) {
  Fixture f;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-3.0, 3.0);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd q = f.randomPosture(rng);
    Eigen::VectorXd qd(7);
    for (int i = 0; i < 7; ++i) qd[i] = U(rng);
    f.set(q, qd);
    const RobotModel::Vector6d hG = f.robot.centroidalMomentum();  // [linear; angular about the CoM], W
    // Only arm bodies move: h_P = h_G + (G - P) x p.
    const Eigen::Vector3d P = f.chain.momentum_point;
    const Eigen::Vector3d ref = hG.tail<3>() + (f.robot.com() - P).cross(hG.head<3>());
    const Eigen::Vector3d h = model::chainAngularMomentum(f.chain, q.data(), qd.data());
    EXPECT_LT((h - ref).norm(), 1e-9 * std::max(1.0, ref.norm())) << h.transpose() << " vs " << ref.transpose();
  }
}

TEST(ArmChain, CentreOfMassMatchesRobotModel) {
  Fixture f;
  std::mt19937 rng(9);
  double m_arm = 0.0;
  for (const auto& L : f.chain.links) m_arm += L.mass;
  const Eigen::VectorXd home = f.chain.homePosture();
  f.set(home, Eigen::VectorXd::Zero(7));
  const Eigen::Vector3d G0 = f.robot.com();
  const Eigen::Vector3d c0 = model::chainCom(f.chain, home.data());
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::VectorXd q = f.randomPosture(rng);
    f.set(q, Eigen::VectorXd::Zero(7));
    // only the arm moves: M (G - G0) = m_arm (c - c0)
    const Eigen::Vector3d lhs = f.robot.totalMass() * (f.robot.com() - G0);
    const Eigen::Vector3d rhs = m_arm * (model::chainCom(f.chain, q.data()) - c0);
    EXPECT_LT((lhs - rhs).norm(), 1e-9) << lhs.transpose() << " vs " << rhs.transpose();
  }
}

// ---- derivatives ----

namespace {

template <class E>
void checkElement(const E& e, const Fixture& f, unsigned seed, double scale_in = 1.0) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  constexpr int ni = E::kInputs, no = E::kOutputs;
  for (int trial = 0; trial < 3; ++trial) {
    std::vector<double> x(ni), w(no), y(no), J(no * ni), H(ni * ni), Hf(ni * ni);
    const Eigen::VectorXd q = const_cast<Fixture&>(f).randomPosture(rng);
    for (int i = 0; i < ni; ++i) x[i] = i < 7 ? q[i] : scale_in * U(rng);
    for (auto& v : w) v = U(rng);
    e.evalJacobian(x.data(), y.data(), J.data());
    const double h = 1e-6;
    for (int i = 0; i < ni; ++i) {  // Jacobian column i by central differences
      std::vector<double> xp = x, xm = x, fp(no), fm(no);
      xp[i] += h, xm[i] -= h;
      e.eval(xp.data(), fp.data());
      e.eval(xm.data(), fm.data());
      for (int j = 0; j < no; ++j) EXPECT_LT(relErr(J[j * ni + i], (fp[j] - fm[j]) / (2 * h)), 1e-6) << e.name();
    }
    e.evalHessian(x.data(), w.data(), H.data());
    for (int i = 0; i < ni; ++i) {  // Hessian row i by central differences of the AD gradient
      std::vector<double> xp = x, xm = x, fp(no), Jp(no * ni), Jm(no * ni);
      xp[i] += h, xm[i] -= h;
      e.evalJacobian(xp.data(), fp.data(), Jp.data());
      e.evalJacobian(xm.data(), fp.data(), Jm.data());
      for (int b = 0; b < ni; ++b) {
        double d = 0.0;
        for (int j = 0; j < no; ++j) d += w[j] * (Jp[j * ni + b] - Jm[j * ni + b]);
        EXPECT_LT(relErr(H[i * ni + b], d / (2 * h)), 1e-6) << e.name() << " H(" << i << "," << b << ")";
      }
    }
    e.evalHessianForward(x.data(), w.data(), Hf.data());
    for (int k = 0; k < ni * ni; ++k) EXPECT_LT(relErr(H[k], Hf[k]), 1e-10) << e.name();
    // Both from one evaluation (what the planner's derivatives call): the same values, to rounding (two summation
    // orders: up to ~2e-14 where the compiler contracts products into FMAs, an AVX2 build).
    std::vector<double> y2(no, -7.0), J2(no * ni, -7.0), H2(ni * ni, -7.0);
    e.evalJacobianHessian(x.data(), w.data(), y2.data(), J2.data(), H2.data());
    for (int j = 0; j < no; ++j) EXPECT_LT(relErr(y2[j], y[j]), 1e-13) << e.name();
    for (int k = 0; k < no * ni; ++k) EXPECT_LT(relErr(J2[k], J[k]), 1e-13) << e.name() << " J[" << k << "]";
    for (int k = 0; k < ni * ni; ++k) EXPECT_LT(relErr(H2[k], H[k]), 1e-13) << e.name() << " H[" << k << "]";
    // Declared constant derivatives are constant (the Ocp evaluates them once).
    std::vector<double> y3(no), J3(no * ni), H3(ni * ni), x2(ni);
    for (auto& v : x2) v = U(rng);
    if (e.jacobianIsConstant()) {
      e.evalJacobian(x2.data(), y3.data(), J3.data());
      for (int k = 0; k < no * ni; ++k) EXPECT_EQ(J3[k], J[k]) << e.name() << " declares a constant Jacobian";
    }
    if (e.hessianIsConstant()) {
      e.evalHessian(x2.data(), w.data(), H3.data());
      for (int k = 0; k < ni * ni; ++k) EXPECT_LT(relErr(H3[k], H[k]), 1e-14) << e.name() << " declares a constant Hessian";
    }
  }
}

}  // namespace

TEST(ArmChain, EveryArmElementMatchesCentralDifferences) {
  Fixture f;
  checkElement(ArmTorqueElement(f.chain), f, 11, 3.0);
  checkElement(ArmEndEffectorElement(f.chain), f, 12);
  checkElement(ArmMomentumCostElement(f.chain, Eigen::Vector3d::UnitY(), false, 0.0), f, 13, 3.0);
  checkElement(ArmMomentumCostElement(f.chain, Eigen::Vector3d::UnitY(), true, 4.0), f, 14, 3.0);
  checkElement(ArmComElement(f.chain), f, 18);
  checkElement(ArmContinuityElement(0.025), f, 15);
  checkElement(DifferenceElement<14>(), f, 16);
  checkElement(SquaredNorm<7>("v"), f, 17);
}

TEST(ArmChain, ElementsAgreeWithTheChainFunctions) {
  Fixture f;
  std::mt19937 rng(21);
  const Eigen::VectorXd q = f.randomPosture(rng);
  Eigen::VectorXd x(21);
  x << q, Eigen::VectorXd::LinSpaced(7, -1, 1), Eigen::VectorXd::LinSpaced(7, 2, -2);
  double out[7];
  ArmTorqueElement(f.chain).eval(x.data(), out);
  double tau[7];
  model::chainInverseDynamics(f.chain, x.data(), x.data() + 7, x.data() + 14, tau);
  for (int i = 0; i < 7; ++i) EXPECT_NEAR(out[i] * f.chain.links[i].tau_max, tau[i], 1e-12);
  double c;
  ArmMomentumCostElement(f.chain, Eigen::Vector3d::UnitY(), false, 0.0).eval(x.data(), &c);
  EXPECT_NEAR(c, -model::chainAngularMomentum(f.chain, x.data(), x.data() + 7).y(), 1e-12);
}

// The assembled arm-flywheel NLP (a short horizon, both cost forms and the CoM bound): objective gradient,
// constraint Jacobian and Lagrangian Hessian against central finite differences at a perturbed guess.
TEST(ArmChain, AssembledArmFlywheelNlpMatchesCentralDifferences) {
  for (const std::string mode : {"tracking", "linear"}) {
    const ArmFlywheelProblem problem(loadArmFlywheelConfig(
        "", {"horizon.intervals=8", "cost.momentum_mode=" + mode, "workspace.com_x_offset=0.1", "phase_anchor=true"}));
    const Ocp& ocp = problem.ocp();
    const int n = ocp.numVariables(), m = ocp.numConstraints();
    std::mt19937 rng(31);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    Eigen::VectorXd z = ocp.guess();
    for (int i = 0; i < n; ++i) z[i] += 0.1 * U(rng) * ocp.scale()[i];
    Eigen::VectorXd lambda(m);
    for (int j = 0; j < m; ++j) lambda[j] = U(rng);
    centaur::test::expectNlpMatchesCentralDifferences(ocp, z, lambda, 0.7, mode);
  }
}
