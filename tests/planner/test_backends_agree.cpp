// ctest-labels: physics integration
// The two OCP backends (Ipopt + MUMPS, the reference; our interior point with the stage-wise KKT solver) on the
// shipped problems from their default guesses: both converge, and they reach the same local optimum (objective
// within 1e-6 relative, the same 1 kHz primitive within 1 mm / 10 N) -- or, where the test names the problem, two
// different points of a nearly flat valley that are each a KKT point for both backends (a warm start of one
// backend from the other's solution stays there).
#include <gtest/gtest.h>

#include <cmath>

#include "planner/arm_flywheel_problem.hpp"
#include "planner/jump_problem.hpp"
#include "planner/solve_ocp.hpp"
#include "planner/solve_with.hpp"

using namespace centaur;
using namespace centaur::planner;
using centaur::test::solveWith;

namespace {

double relDiff(double a, double b) { return std::abs(a - b) / std::max(1.0, std::abs(b)); }

void expectConverged(const SolveResult& r, const std::string& what, double constr_viol_tol) {
  EXPECT_EQ(r.info.status, "solved") << what;
  EXPECT_LT(r.info.max_constraint_violation, constr_viol_tol) << what;
}

// Largest difference of two sampled matrices with the same columns over the common rows.
double maxDiff(const data::RowMatrix& a, const data::RowMatrix& b) {
  const Eigen::Index n = std::min(a.rows(), b.rows());
  return (a.topRows(n) - b.topRows(n)).cwiseAbs().maxCoeff();
}

}  // namespace

TEST(BackendsAgree, HalfSquatJumpSameOptimumAndPrimitive) {
  const JumpProblem p(loadJumpConfig("half-squat-jump", "", {}));
  const SolverSettings& s = p.config().solver;
  const SolveResult ip = solveWith(p.ocp(), s, "ipopt"), ri = solveWith(p.ocp(), s, "riccati");
  expectConverged(ip, "ipopt", s.constr_viol_tol);
  expectConverged(ri, "riccati", s.constr_viol_tol);
  EXPECT_LT(relDiff(ri.info.cost, ip.info.cost), 1e-6) << ri.info.cost << " vs " << ip.info.cost;
  const data::Primitive a = p.toPrimitive(ip), b = p.toPrimitive(ri);
  EXPECT_NEAR(a.t[a.samples() - 1], b.t[b.samples() - 1], 1.5e-3);
  EXPECT_LT(maxDiff(a.base_pos, b.base_pos), 1e-3);
  EXPECT_LT(maxDiff(a.foot_pos, b.foot_pos), 1e-3);
  // The objective fixes the step sizes only to ~1e-4 s at tol 1e-8 (a flat valley), so the 1 kHz grids of the two
  // solutions are shifted by up to a sample and forces that change quickly differ by a few newtons there (11 N of
  // peaks of ~2 kN; 7 N with the foot dynamics' derivatives by AD, which round differently).
  EXPECT_LT(maxDiff(a.force, b.force), 15.0);
  EXPECT_LT((a.knot_dt - b.knot_dt).cwiseAbs().maxCoeff(), 1e-3);
}

TEST(BackendsAgree, ArmFlywheelSameOptimumAndTrajectory) {
  const ArmFlywheelProblem p(loadArmFlywheelConfig("", {"phase_anchor=true"}));  // without: a free time shift
  const SolverSettings& s = p.config().solver;
  const SolveResult ip = solveWith(p.ocp(), s, "ipopt"), ri = solveWith(p.ocp(), s, "riccati");
  expectConverged(ip, "ipopt", s.constr_viol_tol);
  expectConverged(ri, "riccati", s.constr_viol_tol);
  EXPECT_LT(relDiff(ri.info.cost, ip.info.cost), 1e-6) << ri.info.cost << " vs " << ip.info.cost;
  const data::ArmTrajectory a = p.toTrajectory(ip), b = p.toTrajectory(ri);
  EXPECT_LT(maxDiff(a.q, b.q), 1e-3);    // [rad]
  EXPECT_LT(maxDiff(a.tau, b.tau), 1.0);  // [N m]
}

// The squat jump's optimum lies in a nearly flat valley along the phase durations: from the default guess the
// backends stop at points ~0.08 s apart in total duration whose objectives differ by a few 1e-6 relative. Each
// point is a KKT point for the other backend too: warm-started there, it stays (same objective within 1e-6).
TEST(BackendsAgree, SquatJumpFlatValleyBothPointsAreKktPointsOfBoth) {
  const JumpProblem p(loadJumpConfig("squat-jump", "", {}));
  const SolverSettings& s = p.config().solver;
  const SolveResult ip = solveWith(p.ocp(), s, "ipopt"), ri = solveWith(p.ocp(), s, "riccati");
  expectConverged(ip, "ipopt", s.constr_viol_tol);
  expectConverged(ri, "riccati", s.constr_viol_tol);
  EXPECT_LT(relDiff(ri.info.cost, ip.info.cost), 1e-4) << ri.info.cost << " vs " << ip.info.cost;
  const SolveResult ri_from_ip = solveWith(p.ocp(), s, "riccati", &ip.z);
  const SolveResult ip_from_ri = solveWith(p.ocp(), s, "ipopt", &ri.z);
  expectConverged(ri_from_ip, "riccati warm-started at Ipopt's optimum", s.constr_viol_tol);
  expectConverged(ip_from_ri, "ipopt warm-started at riccati's optimum", s.constr_viol_tol);
  EXPECT_LT(relDiff(ri_from_ip.info.cost, ip.info.cost), 1e-6) << ri_from_ip.info.cost << " vs " << ip.info.cost;
  EXPECT_LT(relDiff(ip_from_ri.info.cost, ri.info.cost), 1e-6) << ip_from_ri.info.cost << " vs " << ri.info.cost;
  std::printf("squat jump: ipopt %.10g (%d it), riccati %.10g (%d it); riccati from ipopt %.10g (%d it), "
              "ipopt from riccati %.10g (%d it)\n",
              ip.info.cost, ip.info.iterations, ri.info.cost, ri.info.iterations, ri_from_ip.info.cost,
              ri_from_ip.info.iterations, ip_from_ri.info.cost, ip_from_ri.info.iterations);
}
