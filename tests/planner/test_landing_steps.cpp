// ctest-labels: physics integration
// `cost.landing_steps` (off by default): a reward of constant slope for long steps from the landing on, where the
// robot comes to rest and little else fixes how long the steps are. On the default half-squat jump, whose optimum
// already has every one of those steps at dt_max, it leaves the optimum where it is (the reward is zero there) and
// takes the last of them, which the default plan leaves just inside its bound, onto the bound.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "data/primitive.hpp"
#include "planner/jump_problem.hpp"

using namespace centaur;
using namespace centaur::planner;

TEST(LandingSteps, PutTheHalfSquatJumpsLandingStepsAtDtMaxAndKeepItsOptimum) {
  const JumpProblem plain(loadJumpConfig("half-squat-jump", "", {"solver.backend=riccati"}));
  const JumpProblem rewarded(
      loadJumpConfig("half-squat-jump", "", {"solver.backend=riccati", "cost.landing_steps=1e-3"}));
  const SolveResult r0 = plain.solve(false), r1 = rewarded.solve(false);
  ASSERT_TRUE(r0.info.solved());
  ASSERT_TRUE(r1.info.solved());
  const HorizonConfig& h = rewarded.config().horizon;
  const data::Primitive p0 = plain.toPrimitive(r0), p1 = rewarded.toPrimitive(r1);
  double reward = 0.0, farthest0 = 0.0, farthest1 = 0.0;  // the largest distance of a landing step below dt_max
  for (int k = h.landing; k < h.intervals; ++k) {
    reward += 1e-3 * (h.dt_max - p1.knot_dt[k]);
    farthest0 = std::max(farthest0, h.dt_max - p0.knot_dt[k]);
    farthest1 = std::max(farthest1, h.dt_max - p1.knot_dt[k]);
  }
  EXPECT_LT(farthest1, 1e-6) << "every step from the landing on at dt_max, up to the barrier";
  EXPECT_GT(farthest0, 10 * farthest1) << "without the reward the last steps stay inside their bound";
  // The same optimum: the objectives agree, and the reward adds nothing to it.
  EXPECT_LT(std::abs(r1.info.cost - r0.info.cost) / std::abs(r0.info.cost), 1e-6)
      << "with the reward " << r1.info.cost << ", without " << r0.info.cost;
  EXPECT_LT(reward, 1e-6 * std::abs(r0.info.cost));
  EXPECT_NEAR(p1.knot_t[h.intervals], p0.knot_t[h.intervals], 1e-3);  // the same total duration
  std::printf("landing steps below dt_max by at most %.2e s (without the reward %.2e s); %d iterations (without %d)\n",
              farthest1, farthest0, r1.info.iterations, r0.info.iterations);
}
