// ctest-labels: unit
// The pivot threshold of the Riccati recursion's rank split (RiccatiSolver::Options::pivot_tol): a stage row that
// hardly depends on the stage's controls is passed back as a row on the state instead of being eliminated with a
// tiny pivot; the factorization keeps the dense inertia, and refinement makes the solve exact.
#include <gtest/gtest.h>

#include <cmath>

#include "ocp_solver/riccati.hpp"
#include "random_stage_qp.hpp"

using namespace centaur::ocp_solver;
using namespace centaur_test;

namespace {

// One step of iterative refinement on the dense residual: the correction solves the same factorization with the
// residual as right-hand side (rows in assemble()'s order: each stage's own rows, then its dynamics).
Eigen::VectorXd refineOnce(const RiccatiSolver& solver, const std::vector<StageQp>& qp, const Dense& d,
                           const Eigen::VectorXd& v) {
  const Eigen::VectorXd r = d.rhs - d.K * v;
  const int N = static_cast<int>(qp.size()) - 1;
  std::vector<StageRhs> rhs(N + 1);
  int col = 0, row = d.n;
  for (int k = 0; k <= N; ++k) {
    const int n = qp[k].nx + qp[k].nu, mk = static_cast<int>(qp[k].C.rows());
    rhs[k].h = -r.segment(col, n);
    rhs[k].c = -r.segment(row, mk);
    col += n;
    row += mk;
    if (k < N) {
      rhs[k].b = -r.segment(row, qp[k + 1].nx);
      row += qp[k + 1].nx;
    } else {
      rhs[k].b.resize(0);
    }
  }
  std::vector<StageSolution> sol;
  RiccatiVectors ws;
  solver.solve(qp, rhs, sol, ws);
  return v + flatten(qp, sol);
}

}  // namespace

// A stage row that hardly depends on the stage's controls (its control part delta times that of a random row, as
// the planner's touch-down rows when the foot arrives almost at rest): eliminating it by the controls would divide
// by a pivot ~delta and blow up the cost-to-go of the stages before. Below the pivot threshold it is passed back
// as a row on the state; the factorization then has the dense inertia, and the solve, refined on the whole
// system's residual, meets 1e-12.
TEST(Riccati, ARowNearlyFreeOfTheControlsIsPassedBackAndRefinementMakesTheSolveExact) {
  int cases = 0;
  for (unsigned seed = 300; seed < 330; ++seed) {
    Gen g(seed);
    auto qp = nonsingularQp(g, 4, Curvature::kConvex, false, 5, 4);
    StageQp& s = qp[2];
    const int n = s.nx + s.nu, m = static_cast<int>(s.C.rows());
    const double delta = std::pow(10.0, -5.0 - static_cast<double>(seed % 5));  // 1e-5 .. 1e-9
    Eigen::MatrixXd C(m + 1, n);
    C.topRows(m) = s.C;
    C.row(m) = g.mat(1, n);
    C.row(m).tail(s.nu) *= delta;
    Eigen::VectorXd c(m + 1);
    c << s.c, g.u();
    s.C = C;
    s.c = c;
    const Dense d = assemble(qp);
    const Inertia ref = denseInertia(d.K);
    if (ref.zero != 0 || ref.positive != d.n || ref.negative != d.m) continue;  // the row must fit the problem
    ++cases;
    RiccatiSolver solver;
    ASSERT_EQ(solver.factor(qp), RiccatiSolver::Status::kOk) << "seed " << seed;
    EXPECT_EQ(solver.inertia().positive, d.n) << "seed " << seed;
    EXPECT_EQ(solver.inertia().negative, d.m) << "seed " << seed;
    std::vector<StageSolution> sol;
    solver.solve(qp, sol);
    Eigen::VectorXd v = flatten(qp, sol);
    const double first = relativeResidual(d, v);
    EXPECT_LT(first, 100.0 * delta) << "seed " << seed << ": the error is of the order of the dropped part";
    for (int it = 0; it < 2; ++it) v = refineOnce(solver, qp, d, v);
    EXPECT_LT(relativeResidual(d, v), 1e-12) << "seed " << seed << ", delta " << delta << ", first " << first;
  }
  EXPECT_GE(cases, 20);
}
