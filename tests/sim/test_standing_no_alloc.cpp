// ctest-labels: sim unit
// StandingController::tick() and MujocoRobot::controlPeriod() never allocate (every heap allocation of this
// test binary is counted: tests/support/allocation_counter.hpp).
#include <gtest/gtest.h>

#include "support/allocation_counter.hpp"

#include <cstddef>

#include "controller/standing_controller.hpp"
#include "sim/mujoco_robot.hpp"
#include "sim/sim_config.hpp"


using namespace centaur;

TEST(StandingNoAlloc, TickAndControlPeriodDoNotAllocate) {
  sim::SimConfig cfg = sim::loadSimConfig("", "", {"sensors.noise.q=0.001", "sensors.latency_periods=2"});
  sim::MujocoRobot robot(cfg.robot);
  StandingController ctrl(cfg.robot.model_path, StandingParams{});
  RobotState state;
  state.resize(robot.numJoints());
  JointCommand command;
  robot.read(state);
  ctrl.start(state, command);
  robot.write(command);
  for (int k = 0; k < 10; ++k) robot.controlPeriod(ctrl, state, command);  // warm up
  // Sanity: the counter does see allocations.
  long before = centaur_test::heapAllocations();
  void* volatile p = std::malloc(64);
  std::free(p);
  ASSERT_EQ(centaur_test::heapAllocations() - before, 1);
  before = centaur_test::heapAllocations();
  for (int k = 0; k < 200; ++k) robot.controlPeriod(ctrl, state, command);
  EXPECT_EQ(centaur_test::heapAllocations() - before, 0);
  before = centaur_test::heapAllocations();
  ctrl.tick(state, command);
  EXPECT_EQ(centaur_test::heapAllocations() - before, 0);
}
