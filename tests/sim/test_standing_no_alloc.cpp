// ctest-labels: sim unit
// StandingController::tick() and MujocoRobot::controlPeriod() never allocate: malloc/calloc/realloc
// are interposed in this test binary (glibc lets the executable define them) and counted while armed.
#include <gtest/gtest.h>

#include <cstddef>

#include "controller/standing_controller.hpp"
#include "sim/mujoco_robot.hpp"
#include "sim/sim_config.hpp"

extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
}

namespace {
volatile bool g_armed = false;
volatile long g_allocations = 0;
}  // namespace

extern "C" void* malloc(std::size_t n) {
  if (g_armed) ++g_allocations;
  return __libc_malloc(n);
}
extern "C" void* calloc(std::size_t n, std::size_t s) {
  if (g_armed) ++g_allocations;
  return __libc_calloc(n, s);
}
extern "C" void* realloc(void* p, std::size_t n) {
  if (g_armed) ++g_allocations;
  return __libc_realloc(p, n);
}

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
  g_armed = true;
  void* p = std::malloc(64);
  g_armed = false;
  std::free(p);
  ASSERT_EQ(g_allocations, 1);
  g_allocations = 0;
  g_armed = true;
  for (int k = 0; k < 200; ++k) robot.controlPeriod(ctrl, state, command);
  g_armed = false;
  EXPECT_EQ(g_allocations, 0);
  g_allocations = 0;
  g_armed = true;
  ctrl.tick(state, command);
  g_armed = false;
  EXPECT_EQ(g_allocations, 0);
}
