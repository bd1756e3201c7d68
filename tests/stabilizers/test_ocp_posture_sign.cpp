// ctest-labels: physics
// Sign convention of stabilizer 3 on the whole robot model (both arms, the right one mirrored): replaying the
// planned arm-flywheel trajectory with a positive pitch rate omega_y > 0 gives the robot a positive angular
// momentum about y (the arms spin "in the direction of falling", Raibert's flywheel: the reaction on the body
// is a -y torque that slows the pitch); omega_y < 0 reverses it. The pelvis is held at the origin; joint
// velocities are the time derivative of the stabilizer's posture reference.
#include <gtest/gtest.h>

#include <cstdio>

#include "model/robot_model.hpp"
#include "planner/arm_flywheel_problem.hpp"
#include "stabilizers/ocp_posture_stabilizer.hpp"

using namespace centaur;

namespace {

/// The arm-flywheel plan with the embedded defaults, planned once for this test binary.
std::shared_ptr<const data::ArmTrajectory> defaultArmFlywheel() {
  static const auto plan = std::make_shared<const data::ArmTrajectory>(
      planner::planArmFlywheel(planner::loadArmFlywheelConfig("", {})));
  return plan;
}

const std::string kModel = std::string(CENTAUR_SOURCE_DIR) + "/models/centauro/centauro.xml";

struct Replay {
  double mean_hy = 0.0, mean_hx = 0.0, mean_hz = 0.0;
  double fixed_hy = 0.0;  // about the (fixed) torso_2 origin instead of the moving CoM
};

// Mean centroidal angular momentum over one full phase cycle at pitch rate wy.
Replay replay(double wy, const std::string& arms) {
  RobotModel m(kModel);
  OcpPostureParams p;
  p.blend_time = 0.0;
  p.arms = arms;
  OcpPostureStabilizer st(p, defaultArmFlywheel());
  st.start(m.jointNames(), m.homeJoints());
  RobotState s;
  s.resize(m.numJoints());
  s.imu_omega = Eigen::Vector3d(0.0, wy, 0.0);
  const double dt = 0.001;
  const double rate = std::abs(p.gamma_tau * wy);  // d tau / dt
  const int ticks = static_cast<int>(std::lround(1.0 / (rate * dt)));
  Eigen::VectorXd q(m.nq()), v = Eigen::VectorXd::Zero(m.nv());
  q.setZero();
  q[3] = 1.0;
  st.step(s, dt, true);
  Eigen::VectorXd prev = st.postureReference();
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double sum_fixed = 0.0;
  const Eigen::Vector3d O(0.2, 0.0, 0.256);  // torso_2 origin (pelvis at the origin): the plan's momentum point
  for (int k = 0; k < ticks; ++k) {
    st.step(s, dt, true);
    const Eigen::VectorXd& qd_ref = st.postureReference();
    q.tail(m.numJoints()) = 0.5 * (qd_ref + prev);  // midpoint: second-order accurate
    v.tail(m.numJoints()) = (qd_ref - prev) / dt;
    m.update(q, v);
    const RobotModel::Vector6d h = m.centroidalMomentum();
    sum += h.tail<3>();
    sum_fixed += (h.tail<3>() + (m.com() - O).cross(h.head<3>())).y();
    prev = qd_ref;
  }
  Replay r;
  r.mean_hx = sum.x() / ticks, r.mean_hy = sum.y() / ticks, r.mean_hz = sum.z() / ticks;
  r.fixed_hy = sum_fixed / ticks;
  return r;
}

}  // namespace

TEST(OcpPostureSign, PositivePitchRateGivesPositiveArmMomentumAboutY) {
  const auto plan = defaultArmFlywheel();
  ASSERT_TRUE(plan->solve.solved());
  const double plan_hy = plan->h_ang.col(1).mean();  // one arm at the planned speed (period T)
  ASSERT_GT(plan_hy, 0.5);

  const Replay both = replay(0.5, "both");
  // Replayed at d tau/dt = 0.5 / s with T = 1 s: half the planned speed, two arms -> the plan's mean h_y about
  // the plan's point; about the moving CoM (what rotates the body) a little less, same sign.
  EXPECT_NEAR(both.fixed_hy, 2.0 * 0.5 * plan->period * plan_hy, 0.02 * plan_hy);
  EXPECT_GT(both.mean_hy, 0.5 * both.fixed_hy);
  // the mirrored right arm adds the same h_y and cancels the left arm's roll and yaw momentum
  EXPECT_LT(std::abs(both.mean_hx), 0.05 * both.mean_hy);
  EXPECT_LT(std::abs(both.mean_hz), 0.05 * both.mean_hy);

  const Replay left = replay(0.5, "left");
  const Replay right = replay(0.5, "right");
  EXPECT_GT(left.mean_hy, 0.0);
  EXPECT_GT(right.mean_hy, 0.0);
  EXPECT_NEAR(left.mean_hy, right.mean_hy, 0.05 * left.mean_hy);  // mirror: same sign and size

  std::printf("plan mean h_y %.3f N m s (one arm, planned speed); replay at omega_y = 0.5 rad/s: both %.3f about "
              "the CoM (x %.4f, z %.4f), %.3f about torso_2; left %.3f, right %.3f\n",
              plan_hy, both.mean_hy, both.mean_hx, both.mean_hz, both.fixed_hy, left.mean_hy, right.mean_hy);
  const Replay back = replay(-0.5, "both");
  EXPECT_LT(back.mean_hy, 0.0);
  EXPECT_NEAR(back.mean_hy, -both.mean_hy, 0.05 * both.mean_hy);
}
