// ctest-labels: physics integration
// target.wall_height (half-squat jump): the rear wheel centres touch the wall at the asked height and stay there,
// at every 1 kHz sample of the wall phase; 0 (the default) leaves the height to the optimizer as before.
#include <gtest/gtest.h>

#include <cmath>

#include "common/error.hpp"
#include "planner/jump_problem.hpp"

using namespace centaur;
using namespace centaur::planner;

namespace {

/// Max |z - height| of the rear wheel centres over the samples where they are planned on the wall.
double worstWallHeightError(const data::Primitive& p, double height) {
  double worst = 0.0;
  int samples = 0;
  const Eigen::Index start = p.samples() / 2;  // after the ground phase: the rear feet's second contact phase
  for (Eigen::Index j = start; j < p.samples(); ++j) {
    for (int i = 2; i < 4; ++i) {
      if (p.contact(j, i) < 0.5) continue;
      worst = std::max(worst, std::abs(p.foot_pos(j, 3 * i + 2) - height));
      ++samples;
    }
  }
  EXPECT_GT(samples, 100) << "no wall phase found";
  return worst;
}

}  // namespace

TEST(WallHeight, RearWheelsTouchTheWallAtTheAskedHeight) {
  const JumpConfig cfg = loadJumpConfig("half-squat-jump", "", {"target.wall_height=0.22"});
  EXPECT_EQ(cfg.wall_height, 0.22);
  const JumpProblem problem(cfg);
  const SolveResult result = problem.solve(false);
  ASSERT_TRUE(result.info.solved()) << result.info.status;
  const data::Primitive p = problem.toPrimitive(result);
  EXPECT_LT(worstWallHeightError(p, 0.22), 1e-4);
  // On the wall plane too (x = wall + wheel radius), so the height constraint did not move them off it.
  const Eigen::Index last = p.samples() - 1;
  EXPECT_NEAR(p.foot_pos(last, 3 * 2), cfg.wallX() + cfg.wheel_radius, 1e-4);
}

TEST(WallHeight, DefaultIsFreeAndOutOfRangeIsRefused) {
  EXPECT_EQ(loadJumpConfig("half-squat-jump", "", {}).wall_height, 0.0);
  try {
    loadJumpConfig("half-squat-jump", "", {"target.wall_height=-0.1"});
    ADD_FAILURE() << "a negative height was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("target.wall_height"), std::string::npos) << e.what();
  }
}
