// ctest-labels: unit
// RobotModel::shiftBase(dp, dv) after update(q, v, detail) gives what update(q + dp, v + dv, detail) gives, for
// every query the detail level provides: frame poses, velocities, Jacobians (frame, point, world point), CoM,
// mass matrix, bias forces (Galilean invariance), centroidal momentum matrix and momentum, Jdot v.
#include <gtest/gtest.h>

#include <random>

#include "model/robot_model.hpp"

using namespace centaur;
using Detail = RobotModel::Detail;

namespace {
const std::string path = std::string(CENTAUR_SOURCE_DIR) + "/models/centauro/centauro.xml";

struct Case {
  Eigen::VectorXd q, v;
  Eigen::Vector3d dp, dv;
};

Case randomCase(const RobotModel& model, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  Case c;
  c.q.resize(model.nq());
  c.v.resize(model.nv());
  for (int i = 0; i < c.q.size(); ++i) c.q[i] = u(rng);
  c.q.segment<4>(3).normalize();
  c.q.tail(model.numJoints()) += model.homeJoints();
  for (int i = 0; i < c.v.size(); ++i) c.v[i] = 4.0 * u(rng);
  c.dp = Eigen::Vector3d(u(rng), u(rng), u(rng));  // up to 0.5 m per axis
  c.dv = 6.0 * Eigen::Vector3d(u(rng), u(rng), u(rng));  // up to 3 m/s per axis
  return c;
}

// |a - b| <= tol * max(1, |b|), element-wise scale of the whole matrix
template <class A, class B>
void expectNear(const A& a, const B& b, double tol, const std::string& what) {
  const double scale = std::max(1.0, b.cwiseAbs().maxCoeff());
  EXPECT_LE((a - b).cwiseAbs().maxCoeff(), tol * scale) << what;
}

void expectSameQueries(const RobotModel& shifted, const RobotModel& fresh, Detail detail, const std::string& label) {
  const int nv = fresh.nv();
  constexpr double tol = 1e-11;
  expectNear(shifted.q(), fresh.q(), tol, label + " q");
  expectNear(shifted.v(), fresh.v(), tol, label + " v");
  expectNear(shifted.com(), fresh.com(), tol, label + " com");
  RowMatrixXd J1(6, nv), J2(6, nv), P1(3, nv), P2(3, nv);
  for (int f = 0; f < fresh.numFrames(); ++f) {
    const std::string name = label + " frame " + fresh.frameName(f);
    expectNear(shifted.framePose(f).matrix(), fresh.framePose(f).matrix(), tol, name + " pose");
    if (detail != Detail::kMomentum && detail != Detail::kJacobians)
      expectNear(shifted.frameVelocity(f), fresh.frameVelocity(f), tol, name + " velocity");
    shifted.frameJacobian(f, J1);
    fresh.frameJacobian(f, J2);
    expectNear(J1, J2, tol, name + " jacobian");
    const Eigen::Vector3d f_point(0.03, -0.02, 0.05);
    shifted.pointJacobian(f, f_point, P1);
    fresh.pointJacobian(f, f_point, P2);
    expectNear(P1, P2, tol, name + " point jacobian");
    const Eigen::Vector3d w_point = fresh.framePose(f) * f_point;  // the same material point, in W
    shifted.worldPointJacobian(f, w_point, P1);
    fresh.worldPointJacobian(f, w_point, P2);
    expectNear(P1, P2, tol, name + " world point jacobian");
    if (detail == Detail::kFull) {
      expectNear(shifted.frameBiasAcceleration(f), fresh.frameBiasAcceleration(f), tol, name + " Jdot v");
      expectNear(shifted.worldPointBiasAcceleration(f, w_point), fresh.worldPointBiasAcceleration(f, w_point), tol,
                 name + " point Jdot v");
    }
  }
  if (detail == Detail::kFull || detail == Detail::kDynamics) {
    RowMatrixXd M1(nv, nv), M2(nv, nv);
    shifted.massMatrix(M1);
    fresh.massMatrix(M2);
    expectNear(M1, M2, tol, label + " mass matrix");
    Eigen::VectorXd b1(nv), b2(nv);
    shifted.biasForces(b1);
    fresh.biasForces(b2);
    expectNear(b1, b2, tol, label + " bias forces");
  }
  if (detail == Detail::kFull || detail == Detail::kMomentum) {
    RowMatrixXd A1(6, nv), A2(6, nv);
    shifted.centroidalMomentumMatrix(A1);
    fresh.centroidalMomentumMatrix(A2);
    expectNear(A1, A2, tol, label + " CMM");
    expectNear(shifted.centroidalMomentum(), fresh.centroidalMomentum(), tol, label + " h");
    expectNear(shifted.comVelocity(), fresh.comVelocity(), tol, label + " com velocity");
    Eigen::VectorXd g1(nv), g2(nv);
    shifted.gravityForces(g1);
    fresh.gravityForces(g2);
    expectNear(g1, g2, tol, label + " gravity forces");
  }
  if (detail == Detail::kFull) {
    expectNear(shifted.centroidalMomentumBias(), fresh.centroidalMomentumBias(), tol, label + " hbias");
    expectNear(shifted.comBiasAcceleration(), fresh.comBiasAcceleration(), tol, label + " com Jdot v");
  }
}
}  // namespace

TEST(RobotModelShift, ShiftedBaseEqualsAFreshUpdateAtEveryDetailLevel) {
  RobotModel shifted(path), fresh(path);
  const std::pair<Detail, const char*> levels[] = {{Detail::kFull, "full"},
                                                   {Detail::kMomentum, "momentum"},
                                                   {Detail::kDynamics, "dynamics"},
                                                   {Detail::kKinematics, "kinematics"},
                                                   {Detail::kJacobians, "jacobians"}};
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const Case c = randomCase(fresh, seed);
    Eigen::VectorXd q2 = c.q, v2 = c.v;
    q2.head<3>() += c.dp;
    v2.head<3>() += c.dv;
    for (const auto& [detail, name] : levels) {
      shifted.update(c.q, c.v, detail);
      shifted.shiftBase(c.dp, c.dv);
      fresh.update(q2, v2, detail);
      expectSameQueries(shifted, fresh, detail, std::string(name) + " seed " + std::to_string(seed));
    }
  }
}

TEST(RobotModelShift, TheShiftIsNotANoOp) {
  // The comparison above would hold trivially if nothing depended on the base translation: check that poses,
  // velocities and the momentum do change with dp, dv.
  RobotModel a(path), b(path);
  const Case c = randomCase(a, 3);
  a.update(c.q, c.v);
  b.update(c.q, c.v);
  b.shiftBase(c.dp, c.dv);
  const int wheel = a.frameId("wheel_centre_2");
  EXPECT_TRUE((b.framePose(wheel).translation() - a.framePose(wheel).translation()).isApprox(c.dp, 1e-12));
  EXPECT_TRUE((b.frameVelocity(wheel).head<3>() - a.frameVelocity(wheel).head<3>()).isApprox(c.dv, 1e-12));
  EXPECT_TRUE((b.comVelocity() - a.comVelocity()).isApprox(c.dv, 1e-12));
  EXPECT_TRUE(b.centroidalMomentum().tail<3>().isApprox(a.centroidalMomentum().tail<3>(), 1e-12));  // about the CoM
}
