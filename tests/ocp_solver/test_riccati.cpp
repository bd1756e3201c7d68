// ctest-labels: unit
// The structured (Riccati) factorization against dense linear algebra on random stage-structured KKT systems:
// the solution satisfies the whole KKT system to 1e-10 relative residual (mixed, pure-state and pure-control
// rows, fixed or free initial state, stage-varying sizes, the planner's sizes), and the inertia it reports is
// the one a dense eigen-decomposition of the KKT matrix finds: positive definite reduced Hessians, indefinite
// ones, and dependent rows (a rank-deficient constraint Jacobian: zero eigenvalues, status kSingular).
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cstdio>
#include <limits>
#include <random>

#include "ocp_solver/riccati.hpp"
#include "random_stage_qp.hpp"

using namespace centaur::ocp_solver;
using namespace centaur_test;

TEST(Riccati, SolvesRandomConvexStageSystemsToTheDenseResidual) {
  for (unsigned seed = 0; seed < 60; ++seed) {
    Gen g(seed);
    const int N = 1 + seed % 12;
    const bool fix = seed % 2 == 1;
    const auto qp = nonsingularQp(g, N, Curvature::kConvex, fix);
    const Dense d = assemble(qp);
    RiccatiSolver solver;
    ASSERT_EQ(solver.factor(qp), RiccatiSolver::Status::kOk) << "seed " << seed;
    EXPECT_EQ(solver.inertia().positive, d.n) << "seed " << seed;
    EXPECT_EQ(solver.inertia().negative, d.m) << "seed " << seed;
    EXPECT_EQ(solver.inertia().zero, 0) << "seed " << seed;
    std::vector<StageSolution> sol;
    solver.solve(qp, sol);
    EXPECT_LT(relativeResidual(d, flatten(qp, sol)), 1e-10) << "seed " << seed;
  }
}

TEST(Riccati, InertiaMatchesTheDenseEigenDecomposition) {
  int wrong = 0, right = 0;
  for (unsigned seed = 100; seed < 220; ++seed) {
    Gen g(seed);
    const auto qp = nonsingularQp(g, 1 + seed % 6, Curvature::kIndefinite, seed % 3 == 0, 4, 3);
    const Dense d = assemble(qp);
    const Inertia ref = denseInertia(d.K);
    RiccatiSolver full(RiccatiSolver::Options{1e-11, true});
    full.factor(qp);
    EXPECT_EQ(full.inertia().positive, ref.positive) << "seed " << seed;
    EXPECT_EQ(full.inertia().negative, ref.negative) << "seed " << seed;
    EXPECT_EQ(full.inertia().zero, 0) << "seed " << seed;
    // The default mode stops at the first indefinite reduced Hessian: it must say "wrong" exactly when the
    // KKT matrix does not have the inertia (n, m, 0).
    RiccatiSolver fast;
    const bool correct = ref.positive == d.n && ref.negative == d.m;
    EXPECT_EQ(fast.factor(qp) == RiccatiSolver::Status::kOk, correct) << "seed " << seed;
    (correct ? right : wrong)++;
    // With the full inertia the solve still works (the elimination is a congruence with nonsingular pivots).
    std::vector<StageSolution> sol;
    full.solve(qp, sol);
    EXPECT_LT(relativeResidual(d, flatten(qp, sol)), 1e-8) << "seed " << seed;
  }
  EXPECT_GT(wrong, 10);  // both outcomes were exercised
  EXPECT_GT(right, 5);
}

TEST(Riccati, DependentRowsAreZeroEigenvaluesAndConsistentSystemsStillSolve) {
  for (unsigned seed = 300; seed < 340; ++seed) {
    Gen g(seed);
    const int N = 2 + seed % 5;
    auto qp = nonsingularQp(g, N, Curvature::kConvex, false);
    // Dependent rows: at a stage, a combination of two of its rows (or a copy of one); at another stage a
    // pure-state row that repeats, through the dynamics, a pure-state row of the next stage.
    int dependent = 0;
    const int k = g.i(0, N);
    StageQp& s = qp[k];
    const int n = s.nx + s.nu;
    const int m = static_cast<int>(s.C.rows());
    Eigen::RowVectorXd row = g.mat(1, n);
    double rhs = g.u();
    if (m >= 2) {
      row = 0.7 * s.C.row(0) - 1.3 * s.C.row(1);
      rhs = 0.7 * s.c[0] - 1.3 * s.c[1];
    } else if (m == 1) {
      row = 2.0 * s.C.row(0);
      rhs = 2.0 * s.c[0];
    }
    if (m >= 1) {
      s.C.conservativeResize(m + 1, n);
      s.c.conservativeResize(m + 1);
      s.C.row(m) = row;
      s.c[m] = rhs;
      ++dependent;
    }
    // A copy (times -3) of a pure-state row on the terminal state: dependent through the whole recursion.
    StageQp& t = qp[N];
    const int mt = static_cast<int>(t.C.rows());
    if (mt >= 1 && k != N) {
      t.C.conservativeResize(mt + 1, t.nx);
      t.c.conservativeResize(mt + 1);
      t.C.row(mt) = -3.0 * t.C.row(0);
      t.c[mt] = -3.0 * t.c[0];
      ++dependent;
    }
    if (dependent == 0) continue;
    const Dense d = assemble(qp);
    const Inertia ref = denseInertia(d.K);
    RiccatiSolver solver;
    ASSERT_EQ(solver.factor(qp), RiccatiSolver::Status::kSingular) << "seed " << seed;
    EXPECT_EQ(solver.inertia().zero, dependent) << "seed " << seed;
    EXPECT_EQ(solver.inertia().zero, ref.zero) << "seed " << seed;
    EXPECT_EQ(solver.inertia().positive, ref.positive) << "seed " << seed;
    EXPECT_EQ(solver.inertia().negative, ref.negative) << "seed " << seed;
    std::vector<StageSolution> sol;
    solver.solve(qp, sol);
    EXPECT_LT(relativeResidual(d, flatten(qp, sol)), 1e-10) << "seed " << seed;
  }
}

bool sameBits(const std::vector<StageSolution>& a, const std::vector<StageSolution>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k)
    if (!(a[k].x == b[k].x && a[k].u == b[k].u && a[k].lambda == b[k].lambda && a[k].eta == b[k].eta)) return false;
  return true;
}

// Two factorizations of the same problem: the same failing stage and inertia counts.
void expectSameInertia(const RiccatiSolver& a, const RiccatiSolver& b, unsigned seed) {
  EXPECT_EQ(a.failedStage(), b.failedStage()) << "seed " << seed;
  EXPECT_EQ(a.inertia().positive, b.inertia().positive) << "seed " << seed;
  EXPECT_EQ(a.inertia().negative, b.inertia().negative) << "seed " << seed;
  EXPECT_EQ(a.inertia().zero, b.inertia().zero) << "seed " << seed;
}

// ... and the same solution, bit for bit (qa, qb: the problems each was factored with).
void expectSameSolution(RiccatiSolver& a, const std::vector<StageQp>& qa, RiccatiSolver& b,
                        const std::vector<StageQp>& qb, unsigned seed) {
  std::vector<StageSolution> x, y;
  a.solve(qa, x);
  b.solve(qb, y);
  EXPECT_TRUE(sameBits(x, y)) << "seed " << seed;
}

// Dynamics given as sparse columns (StageQp::M, as the planner's KKT solver gives them) give the solution of the
// dense A and B, bit for bit; resize() drops them, so a stage refilled with other dynamics is not solved with stale
// ones.
TEST(Riccati, GivenSparseDynamicsGiveTheDenseBitsAndResizeDropsThem) {
  for (unsigned seed = 500; seed < 530; ++seed) {
    Gen g(seed);
    const int N = 1 + seed % 8;
    const auto qp = nonsingularQp(g, N, Curvature::kConvex, seed % 2 == 1);
    auto given = qp, refilled = qp;
    for (int k = 0; k < N; ++k) {
      sparseColumns(qp[k].A, qp[k].B, static_cast<int>(qp[k].A.rows()), given[k].M);
      StageQp& s = refilled[k];
      sparseColumns(2.0 * qp[k].A, qp[k].B, static_cast<int>(qp[k].A.rows()), s.M);  // of other dynamics
      s.resize(qp[k].nx, qp[k].nu, static_cast<int>(qp[k].C.rows()), static_cast<int>(qp[k].A.rows()));
      s.H = qp[k].H, s.h = qp[k].h, s.A = qp[k].A, s.B = qp[k].B, s.b = qp[k].b, s.C = qp[k].C, s.c = qp[k].c;
    }
    std::vector<StageSolution> ref, from_given, from_refilled;
    RiccatiSolver a, b, c;
    ASSERT_EQ(a.factor(qp), RiccatiSolver::Status::kOk) << "seed " << seed;
    ASSERT_EQ(b.factor(given), RiccatiSolver::Status::kOk) << "seed " << seed;
    ASSERT_EQ(c.factor(refilled), RiccatiSolver::Status::kOk) << "seed " << seed;
    a.solve(qp, ref);
    b.solve(given, from_given);
    c.solve(refilled, from_refilled);
    EXPECT_TRUE(sameBits(ref, from_given)) << "seed " << seed;
    EXPECT_TRUE(sameBits(ref, from_refilled)) << "seed " << seed;
  }
}

TEST(Riccati, PlannerSizedSystem) {
  // The squat jump's sizes: 30 stages, 55 states (37 plus 18 carried controls), 31 controls, 6 mixed rows, 12
  // pure-state rows (pinned feet) on most stages, a fixed initial state.
  Gen g(7);
  const int N = 30;
  std::vector<StageQp> qp(N + 1);
  for (int k = 0; k <= N; ++k) {
    const int nx = 55, nu = k < N ? 31 : 0;
    const int mixed = k < N ? 6 : 0, state = (k > 0 && (k <= 11 || k >= 20)) ? 12 : 0, fixed = k == 0 ? nx : 0;
    StageQp& s = qp[k];
    s.resize(nx, nu, mixed + state + fixed, k < N ? 55 : 0);
    const Eigen::MatrixXd R = g.mat(nx + nu, nx + nu);
    s.H = R * R.transpose() / (nx + nu) + 0.01 * Eigen::MatrixXd::Identity(nx + nu, nx + nu);
    s.h = g.vec(nx + nu);
    for (int j = 0; j < mixed; ++j) s.C.row(j) = g.mat(1, nx + nu);
    for (int j = 0; j < state; ++j) s.C.row(mixed + j).head(nx) = g.mat(1, nx);
    for (int j = 0; j < fixed; ++j) s.C(mixed + state + j, j) = 1.0;
    s.c = g.vec(static_cast<int>(s.C.rows()));
    if (k < N) {
      s.A = Eigen::MatrixXd::Identity(nx, nx) + 0.1 * g.mat(nx, nx);
      s.B = 0.1 * g.mat(nx, nu);
      s.b = g.vec(nx);
    }
  }
  const Dense d = assemble(qp);
  RiccatiSolver solver;
  ASSERT_EQ(solver.factor(qp), RiccatiSolver::Status::kOk);
  EXPECT_EQ(solver.inertia().positive, d.n);
  EXPECT_EQ(solver.inertia().negative, d.m);
  std::vector<StageSolution> sol;
  solver.solve(qp, sol);
  EXPECT_LT(relativeResidual(d, flatten(qp, sol)), 1e-10);
}

TEST(Riccati, ParallelRowPartsGiveBitIdenticalFactorsInertiaAndSolutions) {
  // The row parts of the stages on a second thread ahead of the cost parts (setParallel): the same status,
  // inertia counts and failing stage at every factorization (also when an indefinite stage stops the recursion
  // early, and with dependent rows), the same solution to the last bit, and before_stage called for stages N..0
  // in this order (up to the failing one when the recursion stops early). One solver object
  // each, reused over all instances as the interior point reuses it.
  int early = 0, singular = 0, ok = 0;
  for (const bool full : {false, true}) {
    RiccatiSolver::Options o;
    o.full_inertia = full;
    RiccatiSolver seq(o), par(o);
    par.setParallel(true);
    ASSERT_TRUE(par.parallel());
    for (unsigned seed = 400; seed < 460; ++seed) {
      Gen g(seed);
      const int N = 2 + seed % 7;
      auto qp = randomQp(g, N, seed % 2 == 0 ? Curvature::kIndefinite : Curvature::kConvex, seed % 3 == 0);
      StageQp& s = qp[g.i(0, N)];
      const int m = static_cast<int>(s.C.rows());
      if (seed % 4 == 1 && m >= 1) {  // a dependent row: twice the first one
        s.C.conservativeResize(m + 1, s.C.cols());
        s.c.conservativeResize(m + 1);
        s.C.row(m) = 2.0 * s.C.row(0);
        s.c[m] = 2.0 * s.c[0];
      }
      std::vector<int> seen_seq, seen_par;
      const auto a = seq.factor(qp, [&](int k) { seen_seq.push_back(k); });
      const auto b = par.factor(qp, [&](int k) { seen_par.push_back(k); });
      ASSERT_EQ(a, b) << "seed " << seed;
      expectSameInertia(seq, par, seed);
      const bool stopped = a == RiccatiSolver::Status::kWrongInertia && !full;
      const int last_seq = stopped ? std::max(seq.failedStage(), 0) : 0;
      EXPECT_EQ(static_cast<int>(seen_seq.size()), stopped && seq.failedStage() <= N ? N + 1 - last_seq : N + 1)
          << "seed " << seed;
      // The second thread calls before_stage in the same order, for the same stages or (after an early stop, when it
      // ran ahead) a few more.
      if (stopped) ASSERT_GE(seen_par.size(), seen_seq.size()) << "seed " << seed;
      else ASSERT_EQ(static_cast<int>(seen_par.size()), N + 1) << "seed " << seed;
      for (std::size_t i = 0; i < seen_par.size(); ++i) EXPECT_EQ(seen_par[i], N - static_cast<int>(i)) << "seed " << seed;
      early += stopped;
      singular += a == RiccatiSolver::Status::kSingular;
      ok += a == RiccatiSolver::Status::kOk;
      if (stopped) continue;
      expectSameSolution(seq, qp, par, qp, seed);
    }
  }
  EXPECT_GT(early, 0);
  EXPECT_GT(singular, 0);
  EXPECT_GT(ok, 0);
}

TEST(Riccati, KeptRowPartsGiveTheBitsOfAFullFactorization) {
  // A retry of the inertia correction changes H only: factor(..., same_rows = true) keeps the row parts of the last
  // factorization (and computes those an early stop did not reach). Over growing shifts of H, as the correction
  // tries them, it gives the status, failing stage, inertia and solution of a fresh solver to the last bit,
  // sequential and on two threads.
  int early_then_kept = 0, ok = 0;
  for (const bool parallel : {false, true}) {
    for (unsigned seed = 500; seed < 540; ++seed) {
      Gen g(seed);
      const int N = 3 + seed % 6;
      auto qp = randomQp(g, N, Curvature::kIndefinite, seed % 2 == 0);
      RiccatiSolver kept;
      kept.setParallel(parallel);
      bool stopped = kept.factor(qp) == RiccatiSolver::Status::kWrongInertia;
      for (const double shift : {1e-2, 1.0, 10.0, 100.0}) {
        for (StageQp& s : qp) s.H.diagonal().array() += shift;
        RiccatiSolver fresh;
        const auto a = kept.factor(qp, {}, true);
        const auto b = fresh.factor(qp);
        ASSERT_EQ(a, b) << "seed " << seed << " shift " << shift;
        expectSameInertia(kept, fresh, seed);
        early_then_kept += stopped;
        stopped = a == RiccatiSolver::Status::kWrongInertia;
        if (stopped) continue;
        ++ok;
        expectSameSolution(kept, qp, fresh, qp, seed);
      }
    }
  }
  EXPECT_GT(early_then_kept, 10);
  EXPECT_GT(ok, 40);
}

TEST(Riccati, HFilledByEitherThreadGivesTheBitsOfTheSequentialFactorization) {
  // fill_cost writes each stage's H just before its cost part needs it, on whichever thread is free (the calling one
  // takes a stage whose row part is still running). The problem handed to factor() starts with H poisoned (NaN):
  // every stage the recursion reaches must be filled exactly once, before its cost part reads it, and the result must
  // be the status, failing stage, inertia and solution of the sequential solver on the filled problem, bit for bit,
  // first attempts and retries (same_rows) alike. Stages after an early stop may be filled or not, at most once.
  int early = 0, ok = 0, by_caller = 0, by_worker = 0;
  for (const bool parallel : {false, true}) {
    for (unsigned seed = 600; seed < 660; ++seed) {
      Gen g(seed);
      const int N = 2 + seed % 8;
      auto filled = randomQp(g, N, seed % 2 == 0 ? Curvature::kIndefinite : Curvature::kConvex, seed % 3 == 0);
      RiccatiSolver seq, sut;
      sut.setParallel(parallel);
      for (const double shift : {0.0, 10.0}) {
        for (StageQp& s : filled) s.H.diagonal().array() += shift;
        auto poisoned = filled;
        for (StageQp& s : poisoned) s.H.setConstant(std::numeric_limits<double>::quiet_NaN());
        std::vector<int> fills(N + 1, 0), rows_seen(N + 1, 0);
        std::vector<int> by_thread(2, 0);
        const auto rows = [&](int k) { ++rows_seen[k]; };
        const auto cost = [&](int k, int thread) {
          EXPECT_EQ(rows_seen[k], 1) << "seed " << seed << ": H of stage " << k << " filled before its rows";
          poisoned[k].H = filled[k].H;
          ++fills[k];
          ++by_thread[thread];
        };
        const bool retry = shift > 0.0;
        const auto a = seq.factor(filled, {}, retry);
        const auto b = sut.factor(poisoned, rows, retry, cost);
        ASSERT_EQ(a, b) << "seed " << seed << " shift " << shift;
        expectSameInertia(seq, sut, seed);
        const bool stopped = a == RiccatiSolver::Status::kWrongInertia;
        const int reached = stopped ? std::max(seq.failedStage(), 0) : 0;
        for (int k = 0; k <= N; ++k) {
          if (k >= reached || !stopped) {
            EXPECT_EQ(fills[k], 1) << "seed " << seed << " stage " << k;
          } else {
            EXPECT_LE(fills[k], 1) << "seed " << seed << " stage " << k;
          }
        }
        if (!parallel) {
          EXPECT_EQ(by_thread[1], 0) << "seed " << seed;
        }
        by_caller += parallel ? by_thread[0] : 0;
        by_worker += by_thread[1];
        early += stopped;
        if (stopped) continue;
        ++ok;
        expectSameSolution(seq, filled, sut, poisoned, seed);
      }
    }
  }
  EXPECT_GT(early, 10);
  EXPECT_GT(ok, 40);
  // The parallel solver filled through the callback; which thread took a stage depends on timing (printed).
  EXPECT_GT(by_caller + by_worker, 0);
  std::printf("H filled by the calling thread %d times, by the second %d times\n", by_caller, by_worker);
}
