// ctest-labels: sim physics
// Every shipped robot stands: 5 s of the stand scenario from its home keyframe, in centaur's scene or its own,
// with the standing controller built from its description (frames, foot radius, impedance groups). The base drifts
// less than 1 cm, stays level, and the standing controller's tick() never allocates, for every robot.
#include <gtest/gtest.h>

#include "support/allocation_counter.hpp"

#include <cstdlib>

#include "controller/standing_controller.hpp"
#include "robot/robot_registry.hpp"
#include "sim/mujoco_robot.hpp"
#include "sim/scenario.hpp"
#include "sim/sim_config.hpp"
#include "sim/sim_runner.hpp"
#include "stabilizers/online_stage.hpp"

using namespace centaur;

namespace {

class RobotStands : public ::testing::TestWithParam<std::string> {};

TEST_P(RobotStands, FiveSecondsWithinOneCentimetre) {
  const sim::Scenario stand = sim::standScenario();
  const sim::RunSummary s = sim::runScenario(stand, "", {"robot.name=" + GetParam(), "duration=5"}, {}, {});
  EXPECT_EQ(s.outcome, "success") << GetParam();
  EXPECT_LT(s.pelvis_drift_m, 0.01) << GetParam();
  EXPECT_LT(s.peak_pitch_deg, 1.0) << GetParam();
  EXPECT_LT(s.max_torque_ratio, 1.0) << GetParam();
}

TEST_P(RobotStands, TickNeverAllocates) {
  sim::SimConfig cfg = sim::loadSimConfig(sim::standScenario().defaults_yaml, "", {"robot.name=" + GetParam()});
  EXPECT_EQ(cfg.robot_name, GetParam());
  sim::MujocoRobot robot(cfg.robot);
  YamlReader section = sim::controllerSection(cfg);
  OnlineStageInputs in;
  in.model_path = cfg.robot.model_path;
  in.frames = cfg.frames;
  auto ctrl = makeOnlineController("stand", section, in);
  RobotState state;
  state.resize(robot.numJoints());
  JointCommand command;
  robot.read(state);
  ctrl->start(state, command);
  for (int k = 0; k < 10; ++k) robot.controlPeriod(*ctrl, state, command);  // warm up
  long before = centaur_test::heapAllocations();
  void* volatile p = std::malloc(64);  // the counter sees allocations
  std::free(p);
  ASSERT_EQ(centaur_test::heapAllocations() - before, 1);
  before = centaur_test::heapAllocations();
  for (int k = 0; k < 200; ++k) ctrl->tick(state, command);
  EXPECT_EQ(centaur_test::heapAllocations() - before, 0) << GetParam();
}

INSTANTIATE_TEST_SUITE_P(Robots, RobotStands, ::testing::ValuesIn(robot::robotNames()),
                         [](const ::testing::TestParamInfo<std::string>& i) { return i.param; });

}  // namespace

namespace {

TEST(RobotLayer, ScenarioChoicesWinOverTheRobotsWorldAndTheRobotsControllerFactsWin) {
  // The squat jump moves the wall out of the way for every robot; stand keeps the robot's own wall placement.
  const sim::Scenario* squat = sim::findScenario("squat-jump");
  ASSERT_NE(squat, nullptr);
  for (const auto& name : robot::robotNames()) {
    EXPECT_EQ(sim::loadSimConfig(squat->defaults_yaml, "", {"robot.name=" + name}).robot.wall_x, -20.0) << name;
  }
  const auto robot = robot::loadRobotWithFacts("b2w_z1");
  const sim::SimConfig stand = sim::loadSimConfig(sim::standScenario().defaults_yaml, "", {"robot.name=b2w_z1"});
  const double rear_x = 0.5 * (robot.facts->b_p_foot[2].x() + robot.facts->b_p_foot[3].x());
  EXPECT_NEAR(stand.robot.wall_x, rear_x - 0.15 - robot.facts->foot_radius[2], 1e-4);
  EXPECT_EQ(stand.robot.push.body, "base");
  EXPECT_DOUBLE_EQ(stand.outcome.fall_height, 0.30);  // half of 0.6245 m, down to 5 cm
  // The robot's impedance groups replace the scenario's (CENTAURO's group ankle_pitch is not the B2W's).
  const YAML::Node gains = stand.effective["controller"]["gains"];
  EXPECT_TRUE(gains["knee"]);
  EXPECT_FALSE(gains["ankle_pitch"]);
  // CENTAURO's layer is empty: its effective configuration is the defaults'.
  const sim::SimConfig centauro = sim::loadSimConfig(sim::standScenario().defaults_yaml, "", {});
  EXPECT_EQ(centauro.robot.wall_x, -0.578);
  EXPECT_EQ(centauro.effective["controller"]["gains"]["leg"]["kp"].Scalar(), "1000.0");
}

}  // namespace
