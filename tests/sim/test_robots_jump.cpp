// ctest-labels: sim physics integration
// The squat jump of every shipped robot, planned on its derived template and replayed in closed loop with the
// Raibert stabilizer, ends as docs/validation.md ("Other robots") documents it: CENTAURO lands upright; the
// B2W + Z1 and Spot fall. The run itself works end to end for every robot (its frames,
// legs, radii, gains and Raibert joints from its description), and a primitive of another robot is refused.
#include <gtest/gtest.h>

#include <map>

#include "common/error.hpp"
#include "data/primitive_io.hpp"
#include "planner/jump_problem.hpp"
#include "robot/robot_registry.hpp"
#include "sim/scenario.hpp"
#include "sim/sim_runner.hpp"
#include "support/temp_dir.hpp"

using namespace centaur;

namespace {

// The documented outcome of each robot's squat jump with `raibert` (docs/validation.md).
const std::map<std::string, std::string> kDocumented = {{"centauro", "success"}, {"b2w_z1", "fall"}, {"spot_arm", "fall"}};

class RobotSquatJump : public ::testing::TestWithParam<std::string> {};

TEST_P(RobotSquatJump, EndsAsDocumented) {
  const std::string robot = GetParam();
  ASSERT_TRUE(kDocumented.count(robot)) << robot << ": document its squat jump in docs/robots.md and here";
  centaur_test::TempDir dir{"centaur-robot-jump"};
  const planner::JumpConfig cfg = planner::loadJumpConfig("squat-jump", "", {"robot=" + robot});
  const planner::JumpProblem problem(cfg);
  data::writePrimitive(dir.file("p.h5"), problem.toPrimitive(problem.solve(false)));
  const sim::Scenario* jump = sim::findScenario("squat-jump");
  ASSERT_NE(jump, nullptr);
  const sim::RunSummary s = sim::runScenario(*jump, "", {"robot.name=" + robot},
                                             {{"primitive", dir.file("p.h5")}, {"stabilizer", "raibert"}}, {});
  EXPECT_EQ(s.outcome, kDocumented.at(robot)) << robot;
  if (robot != robot::kDefaultRobot) {  // its primitive on CENTAURO: refused, naming both robots
    try {
      sim::runScenario(*jump, "", {}, {{"primitive", dir.file("p.h5")}}, {});
      ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("'" + robot + "'"), std::string::npos) << e.what();
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Robots, RobotSquatJump, ::testing::ValuesIn(robot::robotNames()),
                         [](const ::testing::TestParamInfo<std::string>& i) { return i.param; });

}  // namespace
