// ctest-labels: physics integration
// Warm starts from a neighbouring primitive (`centaur plan ... --warm-start F.h5[:group]`): the knots of a
// primitive map back to the decision vector exactly and its multipliers come along when they fit the OCP, a
// primitive of another horizon is refused with a message naming its source, and a squat jump warm-started from
// the plan for a target 5 cm lower converges to the optimum of the cold solve (objective within 1e-6 relative)
// in less than half the iterations (the riccati backend), from its knots alone and primal-dual from the
// neighbour's multipliers as well. Ipopt, started primal-dual at its own solution, stays there. The squat jump's
// `cost.last_interval` puts the last step, which the robot rests through, at dt_min, and the re-plan from 0.87 m
// to 0.82 m then takes less than half the iterations of the cold solve.
#include <gtest/gtest.h>

#include <cmath>

#include "common/error.hpp"
#include "data/primitive.hpp"
#include "planner/jump_problem.hpp"

using namespace centaur;
using namespace centaur::planner;

namespace {

std::vector<std::string> withBackend(std::vector<std::string> sets, const std::string& backend) {
  sets.push_back("solver.backend=" + backend);
  return sets;
}

}  // namespace

TEST(WarmStart, KnotsMapBackToTheDecisionVectorAndOtherHorizonsAreRefused) {
  const JumpProblem p(loadJumpConfig("squat-jump", "", {}));
  SolveResult r;
  r.z = p.ocp().guess();
  for (int i = 0; i < r.z.size(); ++i) r.z[i] += 1e-3 * std::sin(0.37 * i) * p.ocp().scale()[i];
  const Eigen::VectorXd z = p.decisionVector(p.toPrimitive(r), "test");
  EXPECT_EQ((z - r.z).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_FALSE(p.warmStart(p.toPrimitive(r), "test").hasMultipliers());  // the solver returned none

  r.y = Eigen::VectorXd::LinSpaced(p.ocp().numConstraints(), -1.0, 1.0);
  r.z_l = Eigen::VectorXd::LinSpaced(r.z.size(), 0.0, 2.0);
  r.z_u = Eigen::VectorXd::LinSpaced(r.z.size(), 3.0, 1.0);
  const WarmStartPoint w = p.warmStart(p.toPrimitive(r), "test");
  ASSERT_TRUE(w.hasMultipliers());
  EXPECT_TRUE(w.z == r.z && w.y == r.y && w.z_l == r.z_l && w.z_u == r.z_u);
  data::Primitive other = p.toPrimitive(r);  // multipliers of an OCP with other rows: the knots alone
  other.mult_constraints.conservativeResize(other.mult_constraints.size() - 4);
  const WarmStartPoint wo = p.warmStart(other, "test");
  EXPECT_FALSE(wo.hasMultipliers());
  EXPECT_TRUE(wo.z == r.z);

  const JumpProblem shorter(loadJumpConfig("squat-jump", "", {"horizon.intervals=12", "horizon.takeoff=4",
                                                              "horizon.landing=8"}));
  SolveResult rs;
  rs.z = shorter.ocp().guess();
  try {
    p.decisionVector(shorter.toPrimitive(rs), "neighbour.h5:squat-jump");
    FAIL() << "a primitive of 12 intervals was accepted for a problem of 30";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("neighbour.h5:squat-jump"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("12 intervals"), std::string::npos) << e.what();
  }
}

TEST(WarmStart, SquatJumpFromANeighbourTargetReachesTheColdOptimum) {
  const std::string backend = "riccati";
  const JumpProblem neighbour(loadJumpConfig("squat-jump", "", withBackend({"target.height=0.87"}, backend)));
  const JumpProblem p(loadJumpConfig("squat-jump", "", withBackend({"target.height=0.92"}, backend)));
  const SolveResult rn = neighbour.solve(false);
  ASSERT_TRUE(rn.info.solved());
  const SolveResult cold = p.solve(false);
  const Eigen::VectorXd x0 = p.decisionVector(neighbour.toPrimitive(rn), "neighbour");
  const SolveResult warm = p.solve(false, &x0);
  ASSERT_TRUE(cold.info.solved());
  ASSERT_TRUE(warm.info.solved());
  EXPECT_LT(std::abs(warm.info.cost - cold.info.cost) / std::abs(cold.info.cost), 1e-6)
      << "warm " << warm.info.cost << " cold " << cold.info.cost;
  EXPECT_LT(warm.info.max_constraint_violation, p.config().solver.constr_viol_tol);
  EXPECT_LT(warm.info.iterations, cold.info.iterations / 2);

  const WarmStartPoint start = p.warmStart(neighbour.toPrimitive(rn), "neighbour");
  ASSERT_TRUE(start.hasMultipliers());
  const SolveResult pd = p.solve(false, start);
  ASSERT_TRUE(pd.info.solved());
  EXPECT_LT(std::abs(pd.info.cost - cold.info.cost) / std::abs(cold.info.cost), 1e-6)
      << "primal-dual warm " << pd.info.cost << " cold " << cold.info.cost;
  EXPECT_LT(pd.info.max_constraint_violation, p.config().solver.constr_viol_tol);
  EXPECT_LT(pd.info.iterations, cold.info.iterations / 2);
  std::printf("%s: cold %d iterations %.3f s, warm %d iterations %.3f s, primal-dual warm %d iterations %.3f s\n",
              backend.c_str(), cold.info.iterations, cold.info.solve_time_s, warm.info.iterations,
              warm.info.solve_time_s, pd.info.iterations, pd.info.solve_time_s);
}

TEST(WarmStart, IpoptStartedPrimalDualAtItsSolutionStaysThere) {
  const JumpProblem p(loadJumpConfig("squat-jump", "", withBackend({}, "ipopt")));
  const SolveResult cold = p.solve(false);
  ASSERT_TRUE(cold.info.solved());
  const data::Primitive prim = p.toPrimitive(cold);
  const WarmStartPoint pd_start = p.warmStart(prim, "itself");
  ASSERT_TRUE(pd_start.hasMultipliers());
  EXPECT_GE(pd_start.z_l.minCoeff(), 0.0);
  EXPECT_GE(pd_start.z_u.minCoeff(), 0.0);
  const Eigen::VectorXd x0 = p.decisionVector(prim, "itself");
  const SolveResult pd = p.solve(false, pd_start), primal = p.solve(false, &x0);
  ASSERT_TRUE(pd.info.solved());
  ASSERT_TRUE(primal.info.solved());
  EXPECT_LT(std::abs(pd.info.cost - cold.info.cost) / std::abs(cold.info.cost), 1e-8)
      << "primal-dual warm " << pd.info.cost << " cold " << cold.info.cost;
  EXPECT_LT(pd.info.iterations, primal.info.iterations);  // 11 and 26
}

// The squat jump's robot is at rest through the last interval, so without `cost.last_interval` only weak terms
// and the barrier of its bounds fix that interval's length (the re-plan from 0.87 m to 0.82 m crawled along it for
// 52 iterations). The cost puts it at dt_min, leaves the optimum's objective where it was, and the re-plan then
// takes less than half the iterations of the cold solve.
TEST(WarmStart, TheLastIntervalCostFixesTheStepTheRobotRestsThroughAndTheReplanIsShort) {
  const JumpProblem p(loadJumpConfig("squat-jump", "", withBackend({}, "riccati")));
  const JumpProblem free_last(loadJumpConfig("squat-jump", "", withBackend({"cost.last_interval=0"}, "riccati")));
  const SolveResult r = p.solve(false), rf = free_last.solve(false);
  ASSERT_TRUE(r.info.solved());
  ASSERT_TRUE(rf.info.solved());
  const double dt_min = p.config().horizon.dt_min;
  const data::Primitive prim = p.toPrimitive(r), prim_free = free_last.toPrimitive(rf);
  const double last = prim.knot_dt[prim.knot_dt.size() - 1];
  const double last_free = prim_free.knot_dt[prim_free.knot_dt.size() - 1];
  EXPECT_NEAR(last, dt_min, 1e-4);  // at the bound, up to the barrier (7.8e-6 s)
  EXPECT_GT(last_free, dt_min + 1e-3);  // inside its bounds: nothing but weak terms holds it there
  EXPECT_LT(std::abs(r.info.cost - rf.info.cost) / std::abs(rf.info.cost), 1e-6)
      << "with the cost " << r.info.cost << ", without " << rf.info.cost;

  const JumpProblem lower(loadJumpConfig("squat-jump", "", withBackend({"target.height=0.82"}, "riccati")));
  const SolveResult cold = lower.solve(false);
  const SolveResult warm = lower.solve(false, lower.warmStart(prim, "the default plan"));
  ASSERT_TRUE(cold.info.solved());
  ASSERT_TRUE(warm.info.solved());
  EXPECT_LT(warm.info.max_constraint_violation, lower.config().solver.constr_viol_tol);
  EXPECT_LT(warm.info.iterations, cold.info.iterations / 2);
  std::printf("last step %.4f s (without the cost %.4f s); 0.82 m cold %d iterations, re-plan %d\n", last,
              last_free, cold.info.iterations, warm.info.iterations);
}
