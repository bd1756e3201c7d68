// ctest-labels: physics integration
// Hard points of docs/planner.md's parameter grids for the riccati backend: what it must do there.
#include <gtest/gtest.h>

#include <cmath>

#include "planner/jump_problem.hpp"
#include "planner/solve_ocp.hpp"
#include "planner/solve_with.hpp"

using namespace centaur;
using namespace centaur::planner;
using centaur::test::solveWith;

// The half-squat jump with the wall 0.25 m away and the rear wheels 0.15 m up. Near its optimum the rear feet reach
// the wall almost at rest, so their touch-down rows at node 20 hardly depend on the controls of interval 19: after
// the elimination of the velocity rows, pivots of 1e-4 to 1e-7. Eliminating such rows there made |E| ~1e6 and the
// cost-to-go of the stages before ill-conditioned: their reduced Hessians looked indefinite, the inertia correction
// asked for primal regularizations of 1 to 1e4 and riccati crawled to max_iter (3000). The pivot threshold passes
// these rows back to the previous stage as rows on the state (RiccatiSolver::Options::pivot_tol).
TEST(RiccatiHardPoints, TouchDownRowsNearlyFreeOfTheLastControlsArePassedBackAndTheSolveConverges) {
  const JumpProblem p(loadJumpConfig(
      "half-squat-jump", "", {"model.preset=centauro", "target.wall_distance=0.25", "target.wall_height=0.15"}));
  const SolverSettings& s = p.config().solver;
  const SolveResult ri = solveWith(p.ocp(), s, "riccati");
  EXPECT_EQ(ri.info.status, "solved");
  EXPECT_LT(ri.info.iterations, 300);
  EXPECT_LT(ri.info.max_constraint_violation, s.constr_viol_tol);
  // A KKT point of the reference: Ipopt, warm-started there, stays.
  const SolveResult ip = solveWith(p.ocp(), s, "ipopt", &ri.z);
  ASSERT_EQ(ip.info.status, "solved");
  const double rel = std::abs(ri.info.cost - ip.info.cost) / std::abs(ip.info.cost);
  EXPECT_LT(rel, 1e-6) << ri.info.cost << " vs Ipopt's " << ip.info.cost << " from riccati's point";
}
