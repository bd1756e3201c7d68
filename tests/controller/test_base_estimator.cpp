// ctest-labels: unit physics
// Base estimator against kinematic ground truth built with an independent RobotModel: static home
// posture (with and without a known start), pure rolling on the wheels, arm motion in stance, ballistic
// flight and touchdown; update() never allocates.
#include <gtest/gtest.h>

#include "support/allocation_counter.hpp"

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>
#include <string>

#include "controller/base_estimator.hpp"

using centaur::BaseEstimator;
using centaur::RobotModel;
using centaur::RobotState;
using centaur::RowMatrixXd;
using Eigen::Quaterniond;
using Eigen::Vector3d;
using Eigen::VectorXd;

namespace {
const std::string kModel = std::string(CENTAUR_SOURCE_DIR) + "/models/centauro/centauro.xml";
constexpr double kHomeZ = 0.64085 + 0.078;  // wheel-centre depth at home + wheel radius (MODEL.md)

struct Truth {
  Vector3d p = Vector3d(0, 0, kHomeZ);
  Quaterniond quat = Quaterniond::Identity();
  VectorXd qj, qdj;
  Vector3d omega = Vector3d::Zero();  // base frame
};

RobotState measure(const Truth& truth, double t) {
  RobotState s;
  s.resize(truth.qj.size());
  s.t = t;
  s.q = truth.qj;
  s.qd = truth.qdj;
  s.imu_quat = truth.quat;
  s.imu_omega = truth.omega;
  return s;
}
}  // namespace


struct BaseEstimatorTest : public ::testing::Test {
  RobotModel model{kModel};
  BaseEstimator est;
  Truth truth;
  const bool all[4] = {true, true, true, true};
  const bool none[4] = {false, false, false, false};
  void SetUp() override {
    est.init(kModel);
    truth.qj = model.homeJoints();
    truth.qdj = VectorXd::Zero(model.numJoints());
  }
};

TEST_F(BaseEstimatorTest, StaticHomeWithoutKnownStartPutsWheelsOnTheGround) {
  for (int k = 0; k < 5; ++k) est.update(measure(truth, 0.001 * k), all);
  EXPECT_LT((est.q().head<3>() - truth.p).norm(), 1e-4) << est.q().head<3>().transpose();
  EXPECT_LT((est.q().segment<4>(3) - Eigen::Vector4d(1, 0, 0, 0)).norm(), 1e-12);
  EXPECT_LT(est.v().norm(), 1e-9);
  EXPECT_LT((est.q().tail(model.numJoints()) - truth.qj).norm(), 1e-15);
}

TEST_F(BaseEstimatorTest, StaticTiltedPoseIsReproducedExactly) {
  truth.p = Vector3d(0.3, -0.2, 0.75);
  truth.quat = Quaterniond(Eigen::AngleAxisd(0.4, Vector3d::UnitZ()) * Eigen::AngleAxisd(0.05, Vector3d::UnitY()));
  est.reset(truth.p);
  for (int k = 0; k < 1000; ++k) est.update(measure(truth, 0.001 * k), all);
  EXPECT_LT((est.q().head<3>() - truth.p).norm(), 1e-12);
  const Quaterniond q_est(est.q()[3], est.q()[4], est.q()[5], est.q()[6]);
  EXPECT_LT(q_est.angularDistance(truth.quat), 1e-12);
  EXPECT_LT(est.v().head<3>().norm(), 1e-9);
  // anchors are the true wheel centres
  VectorXd q(model.nq());
  q << truth.p, truth.quat.w(), truth.quat.x(), truth.quat.y(), truth.quat.z(), truth.qj;
  model.update(q, VectorXd::Zero(model.nv()));
  for (int k = 0; k < 4; ++k)
    EXPECT_LT((est.anchor(k) - model.framePose(model.frameId("wheel_" + std::to_string(k + 1))).translation()).norm(),
              1e-12);
}

TEST_F(BaseEstimatorTest, RollingOnTheWheelsIsTracked) {
  // Drive at 0.5 m/s along the heading (yaw 0.4 rad) by spinning the wheels: v = omega_wheel r.
  const double speed = 0.5, r = 0.078, dt = 0.001, yaw = 0.4;
  truth.quat = Quaterniond(Eigen::AngleAxisd(yaw, Vector3d::UnitZ()));
  const Vector3d heading(std::cos(yaw), std::sin(yaw), 0.0);
  VectorXd q(model.nq());
  q << truth.p, truth.quat.w(), truth.quat.x(), truth.quat.y(), truth.quat.z(), truth.qj;
  model.update(q, VectorXd::Zero(model.nv()));
  for (int k = 1; k <= 4; ++k) {
    // rolling forward needs a wheel angular velocity along (z x heading) = lateral left
    const Vector3d axis = model.framePose(model.frameId("wheel_" + std::to_string(k))).linear().col(2);
    const double sign = axis.dot(Vector3d::UnitZ().cross(heading));
    truth.qdj[model.jointIndex("j_wheel_" + std::to_string(k))] = sign * speed / r;
  }
  const Vector3d p0 = truth.p;
  est.reset(p0);
  Vector3d p_prev_est = p0;
  for (int k = 0; k <= 2000; ++k) {
    const double t = dt * k;
    truth.p = p0 + speed * t * heading;
    for (int w = 1; w <= 4; ++w) {
      const int j = model.jointIndex("j_wheel_" + std::to_string(w));
      truth.qj[j] = model.homeJoints()[j] + truth.qdj[j] * t;
    }
    est.update(measure(truth, t), all);
    if (k > 0) {
      EXPECT_LT((est.v().head<3>() - speed * heading).norm(), 1e-9) << k;
      EXPECT_LT(((est.q().head<3>() - p_prev_est) / dt - speed * heading).norm(), 1e-6) << k;
    }
    p_prev_est = est.q().head<3>();
  }
  EXPECT_LT((est.q().head<3>() - truth.p).norm(), 1e-9) << est.q().head<3>().transpose() << " vs "
                                                         << truth.p.transpose();
}

TEST_F(BaseEstimatorTest, ArmMotionInStanceDoesNotMoveTheBase) {
  est.reset(truth.p);
  const double dt = 0.001;
  for (int k = 0; k <= 500; ++k) {
    const double t = dt * k;
    for (int a = 1; a <= 7; ++a) {
      const int j1 = model.jointIndex("j_arm1_" + std::to_string(a)), j2 = model.jointIndex("j_arm2_" + std::to_string(a));
      truth.qdj[j1] = 0.5 * std::cos(3 * t);
      truth.qdj[j2] = -0.4 * std::cos(2 * t);
      truth.qj[j1] = model.homeJoints()[j1] + 0.5 / 3 * std::sin(3 * t);
      truth.qj[j2] = model.homeJoints()[j2] - 0.4 / 2 * std::sin(2 * t);
    }
    truth.qdj[model.jointIndex("torso_yaw")] = 0.3;
    truth.qj[model.jointIndex("torso_yaw")] = 0.3 * t;
    est.update(measure(truth, t), all);
    EXPECT_LT((est.q().head<3>() - truth.p).norm(), 1e-12);
    EXPECT_LT(est.v().head<3>().norm(), 1e-9);
  }
}

TEST_F(BaseEstimatorTest, FlightIsBallisticAndTouchdownAnchorsTheWheels) {
  const Vector3d p0(0.1, 0.0, 0.80), v0(0.4, -0.1, 1.5), g(0, 0, -9.81);
  est.reset(p0, v0);
  const double dt = 0.001;
  for (int k = 0; k <= 200; ++k) {
    const double t = dt * k;
    est.update(measure(truth, t), none);
    const Vector3d p = p0 + v0 * t + 0.5 * g * t * t;
    EXPECT_LT((est.q().head<3>() - p).norm(), 1e-9) << k;
    EXPECT_LT((est.v().head<3>() - (v0 + g * t)).norm(), 1e-9) << k;
  }
  // touchdown: stays where it landed while static
  const Vector3d landed = est.q().head<3>();
  for (int k = 201; k <= 300; ++k) est.update(measure(truth, dt * k), all);
  EXPECT_LT((est.q().head<3>() - landed).norm(), 1e-12);
  EXPECT_LT(est.v().head<3>().norm(), 1e-9);
}

TEST_F(BaseEstimatorTest, UpdateDoesNotAllocate) {
  RobotState s = measure(truth, 0.0);
  est.update(s, all);
  const long before = centaur_test::heapAllocations();
  const bool some[4] = {true, false, true, false};
  for (int k = 1; k < 10; ++k) {
    s.t = 0.001 * k;
    est.update(s, k < 4 ? all : (k < 7 ? none : some));
  }
  EXPECT_EQ(centaur_test::heapAllocations() - before, 0);
}

TEST_F(BaseEstimatorTest, OnTheCallersModelTheEstimateIsTheSameAndTheModelEndsAtIt) {
  // The controller lets the estimator update its measured model (once, at the prediction) and shift it to the
  // estimate. Through stance with rolling wheels and moving joints, flight and touchdown: the estimate equals the
  // private-model one, and the caller's model equals a fresh update at (q(), v()).
  BaseEstimator own;
  own.init(kModel);
  RobotModel caller(kModel), fresh(kModel);
  const int nv = model.nv();
  RowMatrixXd M1(nv, nv), M2(nv, nv), J1(6, nv), J2(6, nv);
  VectorXd b1(nv), b2(nv);
  own.reset(Vector3d(0.0, 0.0, kHomeZ), Vector3d(0.3, 0.0, 0.0));
  est.reset(Vector3d(0.0, 0.0, kHomeZ), Vector3d(0.3, 0.0, 0.0));
  truth.quat = Quaterniond(Eigen::AngleAxisd(0.1, Vector3d::UnitY()));
  truth.omega = Vector3d(0.05, -0.2, 0.1);
  const double dt = 0.001;
  const int wheel = model.frameId("wheel_centre_3");
  for (int k = 0; k < 300; ++k) {
    const double t = dt * k;
    for (int i = 0; i < truth.qj.size(); ++i) truth.qdj[i] = 0.3 * std::sin(0.7 * i + 20.0 * t);
    truth.qj += dt * truth.qdj;
    const bool* stance = k < 100 ? all : (k < 200 ? none : all);  // stance, flight, touchdown
    own.update(measure(truth, t), stance);
    est.update(measure(truth, t), stance, caller, RobotModel::Detail::kDynamics);
    ASSERT_LT((est.q() - own.q()).cwiseAbs().maxCoeff(), 1e-12) << k;
    ASSERT_LT((est.v() - own.v()).cwiseAbs().maxCoeff(), 1e-12) << k;
    fresh.update(est.q(), est.v(), RobotModel::Detail::kDynamics);
    EXPECT_LT((caller.framePose(wheel).matrix() - fresh.framePose(wheel).matrix()).cwiseAbs().maxCoeff(), 1e-12) << k;
    EXPECT_LT((caller.frameVelocity(wheel) - fresh.frameVelocity(wheel)).cwiseAbs().maxCoeff(), 1e-11) << k;
    caller.frameJacobian(wheel, J1);
    fresh.frameJacobian(wheel, J2);
    EXPECT_LT((J1 - J2).cwiseAbs().maxCoeff(), 1e-12) << k;
    caller.massMatrix(M1);
    fresh.massMatrix(M2);
    EXPECT_LT((M1 - M2).cwiseAbs().maxCoeff(), 1e-11) << k;
    caller.biasForces(b1);
    fresh.biasForces(b2);
    EXPECT_LT((b1 - b2).cwiseAbs().maxCoeff(), 1e-10) << k;
  }
  EXPECT_GT((est.q().head<3>() - Vector3d(0.0, 0.0, kHomeZ)).norm(), 0.01);  // it did move: the shift is exercised
}

TEST_F(BaseEstimatorTest, UpdateOnTheCallersModelDoesNotAllocate) {
  RobotModel caller(kModel);
  RobotState s = measure(truth, 0.0);
  est.update(s, all, caller, RobotModel::Detail::kDynamics);
  const long before = centaur_test::heapAllocations();
  const bool some[4] = {true, false, true, false};
  for (int k = 1; k < 10; ++k) {
    s.t = 0.001 * k;
    est.update(s, k < 4 ? all : (k < 7 ? none : some), caller, RobotModel::Detail::kDynamics);
  }
  EXPECT_EQ(centaur_test::heapAllocations() - before, 0);
}

TEST(BaseEstimatorContactPoint, LowestRimPointForTiltedWheels) {
  // axis horizontal: straight below the centre
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(M_PI / 2, Vector3d::UnitX()).toRotationMatrix();  // z axis -> -y
  T.translation() = Vector3d(1, 2, 0.078);
  EXPECT_LT((BaseEstimator::contactPoint(T, 0.078) - Vector3d(1, 2, 0)).norm(), 1e-12);
  // axis tilted by 30 deg about x: the rim's lowest point is r cos(30 deg) below the centre
  T.linear() = Eigen::AngleAxisd(M_PI / 2 + M_PI / 6, Vector3d::UnitX()).toRotationMatrix();
  const Vector3d c = BaseEstimator::contactPoint(T, 0.1);
  EXPECT_NEAR(c.z(), 0.078 - 0.1 * std::cos(M_PI / 6), 1e-12);
  EXPECT_NEAR((c - T.translation()).norm(), 0.1, 1e-12);
  EXPECT_NEAR((c - T.translation()).dot(T.linear().col(2)), 0.0, 1e-12);
}
