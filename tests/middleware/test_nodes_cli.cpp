// ctest-labels: middleware integration cli
// Bad input to the nodes: unknown tasks and options, a missing primitive, configuration values out of range
// -> exit code 2 with the option or key named, quickly, and no process left behind (each exits by itself).
#include <gtest/gtest.h>

#include "support/node_pair.hpp"

using namespace centaur_test;

TEST(NodesCli, BadInputExitsTwoNamingTheKeyAndLeavesNothingRunning) {
  const TempDir dir("nodes-cli");
  struct Case {
    std::vector<std::string> args;
    std::string must_contain;
  };
  const std::vector<Case> cases = {
      {{"robot", "dance"}, "dance"},
      {{"robot", "stand", "--bogus"}, "--bogus"},
      {{"robot", "stand", "--realtime", "--lockstep"}, "--lockstep"},
      {{"robot", "stand", "--set", "safety.max_kp=-1"}, "safety.max_kp"},
      {{"robot", "stand", "--set", "middleware.domain=999"}, "middleware.domain"},
      {{"robot", "stand", "--set", "middleware.interface=eth0;rm"}, "middleware.interface"},
      {{"robot", "stand", "--set", "robot_node.bogus=1"}, "robot_node.bogus"},
      {{"robot", "stand", "--set", "world.friction=99"}, "world.friction"},
      {{"control", "dance"}, "dance"},
      {{"control", "stand", "--bogus"}, "--bogus"},
      {{"control", "squat-jump"}, "--primitive"},
      {{"control", "squat-jump", "--primitive", dir.file("none.h5")}, "none.h5"},
      {{"control", "squat-jump", "--primitive", dir.file("p.h5"), "--stabilizer", "magic"}, "magic"},
      {{"control", "squat-jump", "--primitive", dir.file("p.h5"), "--stabilizer", "ocp"}, "flywheel"},
      {{"control", "stand", "--start-after", "1"}, "--start-after"},
      {{"control", "stand", "--set", "control_node.stale_time=0"}, "control_node.stale_time"},
      {{"control", "stand", "--set", "controller.friction=0"}, "controller.friction"},
      {{"control", "stand", "--set", "control_period=1"}, "control_period"},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Case& c = cases[i];
    ChildProcess p(CENTAUR_BIN, c.args, dir.file("case" + std::to_string(i) + ".log"));
    ASSERT_TRUE(p.wait(60.0)) << c.args[1] << ": still running";
    EXPECT_EQ(p.code(), 2) << p.output();
    EXPECT_NE(p.output().find(c.must_contain), std::string::npos) << "missing '" << c.must_contain << "' in\n"
                                                                   << p.output();
  }
}
