// ctest-labels: sim integration
// CENTAURO stands 5 s in MuJoCo under the whole-body controller (HQP velocity IK on config/stack_stand.yaml,
// contact detection, force distribution feed-forward): pelvis drift < 1 cm, small tilt, no joint beyond its
// limits, the controller never leaves its nominal mode and detects all four wheels in stance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "controller/whole_body_controller.hpp"
#include "sim/mujoco_robot.hpp"
#include "sim/sim_config.hpp"
#include "sim/sim_runner.hpp"

using namespace centaur;
using namespace centaur::sim;

TEST(WholeBodyStand, CentauroStandsFiveSecondsUnderTheWholeBodyController) {
  SimConfig cfg = loadSimConfig("", "", {"duration=5"});
  MujocoRobot robot(cfg.robot);
  WholeBodyParams p;
  p.stack_file = std::string(CENTAUR_SOURCE_DIR) + "/config/stack_stand.yaml";
  p.dt = cfg.robot.timestep * cfg.robot.control_decimation;
  WholeBodyController ctrl(cfg.robot.model_path, p);
  const RunSummary s = runSimulation(robot, ctrl, cfg, RunOutputs{}, "whole_body_stand");
  std::printf("drift %.4f m, pitch %.3f deg, roll %.3f deg, limit violation %.2e rad, torque ratio %.2f\n",
              s.pelvis_drift_m, s.peak_pitch_deg, s.peak_roll_deg, s.max_joint_limit_violation, s.max_torque_ratio);
  EXPECT_EQ(s.outcome, "success");
  EXPECT_EQ(s.control_periods, 5000);
  EXPECT_LT(s.pelvis_drift_m, 0.01);
  EXPECT_LT(s.peak_pitch_deg, 1.0);
  EXPECT_LT(s.peak_roll_deg, 1.0);
  EXPECT_LE(s.max_joint_limit_violation, 0.0);
  EXPECT_LT(s.max_torque_ratio, 1.0);
  EXPECT_EQ(ctrl.status(), WholeBodyStatus::kOk);
  EXPECT_EQ(ctrl.counters().safe_ticks, 0);
  EXPECT_EQ(ctrl.counters().qp_failures, 0);
  EXPECT_EQ(ctrl.counters().force_failures, 0);
  for (int k = 0; k < 4; ++k) EXPECT_TRUE(ctrl.stance()[k]) << "wheel " << k + 1;
  // the IK held the feet: every pelvis -> wheel reference is met to 1 mm
  for (int k = 1; k <= 4; ++k) {
    const auto& t = ctrl.stack().tasks.at("wheel_" + std::to_string(k));
    EXPECT_LT(t->b().head<3>().norm(), 1e-3) << "wheel " << k;
  }
}

TEST(WholeBodyStand, ArmSwingsWhileTheFeetAndPelvisHold) {
  // At t = 0.5 s the posture reference of both shoulders (j_arm*_1) moves by 0.6 rad: the arms follow
  // (posture level, the angular-momentum task in the same level damps the motion) while the pelvis stays
  // within 1 cm and the estimator's base stays level.
  SimConfig cfg = loadSimConfig("", "", {});
  MujocoRobot robot(cfg.robot);
  WholeBodyParams p;
  p.stack_file = std::string(CENTAUR_SOURCE_DIR) + "/config/stack_stand.yaml";
  p.dt = robot.controlPeriodSeconds();
  WholeBodyController ctrl(cfg.robot.model_path, p);
  RobotState state;
  state.resize(robot.numJoints());
  JointCommand command;
  robot.read(state);
  ctrl.start(state, command);
  const Eigen::Vector3d p0 = robot.basePosition();
  const RobotModel& m = ctrl.ikModel();
  Eigen::VectorXd q_d = m.homeJoints();
  for (int i = 0; i < m.numJoints(); ++i) {
    if (m.jointNames()[static_cast<std::size_t>(i)].find("wheel") != std::string::npos) q_d[i] = state.q[i];
  }
  const int a1 = m.jointIndex("j_arm1_1"), a2 = m.jointIndex("j_arm2_1");
  double drift = 0.0;
  for (int k = 0; k < 3000; ++k) {
    if (k == 500) {
      q_d[a1] += 0.6;
      q_d[a2] -= 0.6;
      ctrl.setPostureReference(q_d);
    }
    robot.controlPeriod(ctrl, state, command);
    drift = std::max(drift, (robot.basePosition() - p0).norm());
    ASSERT_EQ(ctrl.status(), WholeBodyStatus::kOk) << "tick " << k;
  }
  Eigen::VectorXd q(robot.numJoints());
  robot.jointPositions(q);
  std::printf("arm errors %.4f %.4f rad (q_ref %.4f %.4f), drift %.4f m\n", q[a1] - q_d[a1], q[a2] - q_d[a2],
              command.q_ref[a1] - q_d[a1], command.q_ref[a2] - q_d[a2], drift);
  EXPECT_NEAR(q[a1], q_d[a1], 0.05);
  EXPECT_NEAR(q[a2], q_d[a2], 0.05);
  EXPECT_LT(drift, 0.01);
  for (int k = 0; k < 4; ++k) EXPECT_TRUE(ctrl.stance()[k]) << "wheel " << k + 1;
}
