// ctest-labels: sim
// The jump controller's 1 kHz tick (replay + stabilizer + whole-body controller) never allocates: 2000 closed-
// loop periods of the squat jump (push-off, flight and landing) with each stabilizer, zero heap allocations.
#include <gtest/gtest.h>

#include "planner/jump_problem.hpp"
#include "sim/mujoco_robot.hpp"
#include "sim/scenario.hpp"
#include "sim/sim_config.hpp"
#include "stabilizers/jump_controller.hpp"
#include "stabilizers/make_stabilizer.hpp"
#include "support/allocation_counter.hpp"

using namespace centaur;
using namespace centaur::sim;

TEST(JumpController, TicksNeverAllocateThroughPushOffFlightAndLanding) {
  const planner::JumpProblem problem(planner::loadJumpConfig("squat-jump", "", {}));
  const data::Primitive primitive = problem.toPrimitive(problem.solve(false));
  for (const char* mode : {"none", "raibert", "angmom"}) {
    SimConfig cfg = loadSimConfig(findScenario("squat-jump")->defaults_yaml, "", {"controller.settle_time=0"});
    MujocoRobot robot(cfg.robot);
    YamlReader section = controllerSection(cfg);
    JumpControllerParams params;
    params.read(section);
    auto stabilizer = makeStabilizer(mode, section);
    section.finish();
    params.wbc.dt = robot.controlPeriodSeconds();
    JumpController ctrl(cfg.robot.model_path, primitive, std::move(stabilizer), params);
    RobotState state;
    state.resize(robot.numJoints());
    JointCommand command;
    robot.read(state);
    ctrl.start(state, command);
    const long before = centaur_test::heapAllocations();
    bool flew = false;
    for (int k = 0; k < 2000; ++k) {
      robot.controlPeriod(ctrl, state, command);
      const auto& st = ctrl.wholeBody().stance();
      flew = flew || (!st[0] && !st[1] && !st[2] && !st[3]);
    }
    EXPECT_EQ(centaur_test::heapAllocations() - before, 0) << mode;
    EXPECT_TRUE(flew) << mode << ": the 2000 periods must include the flight";
    EXPECT_FALSE(ctrl.wholeBody().inSafeMode()) << mode;
  }
}
