// ctest-labels: unit
// The stage-wise KKT solver against the dense KKT system on random OCP-shaped sparsity: dynamics rows with a
// non-unit entry on x_{k+1}, local rows (mixed, pure-state, pure-control), rows coupling x_k and x_{k+1}
// (substituted), a rate cost between u_k and u_{k+1} and a periodicity row between x_0 and x_N (carried
// variables), fixed variables, inequality rows (penalties) and a dual regularization of the equality rows
// (the dynamics stay exact). Same step and multipliers as the dense solve; kWrongInertia exactly when the dense
// matrix does not have the inertia (n, m, 0).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "dense_kkt.hpp"
#include "ocp_solver/stage_kkt.hpp"

using namespace centaur::ocp_solver;
using centaur_test::DenseKkt;

namespace {

struct Problem {
  SparsePattern p;
  StageLayout layout;
  std::vector<char> fixed, equality;
  std::vector<double> hess, jac;
  Eigen::VectorXd dx, dc, rx, rc;
};

Problem randomProblem(unsigned seed, bool convex, double delta_c) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  const int N = 3 + seed % 5, nx = 3, nu = 2;
  Problem q;
  auto X = [&](int k, int j) { return k * (nx + nu) + j; };
  auto Uv = [&](int k, int j) { return k * (nx + nu) + nx + j; };
  q.p.n = N * (nx + nu) + nx;
  q.layout.num_stages = N + 1;
  for (int v = 0; v < q.p.n; ++v) {
    q.layout.stage.push_back(std::min(v / (nx + nu), N));
    q.layout.is_state.push_back(v % (nx + nu) < nx || v >= N * (nx + nu));
  }
  q.fixed.assign(q.p.n, 0);
  q.fixed[X(0, 1)] = 1;
  q.fixed[Uv(1, 0)] = 1;
  int row = 0;
  auto addRow = [&](const std::vector<int>& vars, bool eq) {
    for (int v : vars) {
      q.p.jac_rows.push_back(row);
      q.p.jac_cols.push_back(v);
      q.jac.push_back(U(rng));
    }
    q.equality.push_back(eq);
    ++row;
  };
  for (int k = 0; k < N; ++k) {
    for (int j = 0; j < nx; ++j) {
      addRow({X(k + 1, j), X(k, j), X(k, (j + 1) % nx), Uv(k, j % nu)}, true);
      q.jac[q.jac.size() - 4] = 0.5 + 0.5 * std::abs(U(rng));  // the entry on x_{k+1}
    }
    addRow({X(k, 0), Uv(k, 0), Uv(k, 1)}, true);       // mixed
    if (k > 0 && k % 2 == 0) addRow({X(k, 2), X(k, 0)}, true);  // pure state
    addRow({Uv(k, 0), Uv(k, 1), X(k, 1)}, false);      // inequality
    if (k == 2) addRow({X(k, 0), X(k, 1), X(k + 1, 0), X(k + 1, 1)}, true);  // coupled to the next state
    if (k == 1) addRow({X(k, 2), Uv(k, 1), X(k + 1, 0)}, false);  // an inequality coupled to the next state
  }
  addRow({X(N, 1), X(N, 2)}, false);
  addRow({X(0, 0), X(N, 0)}, true);  // periodicity
  q.p.m = row;
  // Hessian (lower triangle): stage blocks, a rate coupling u_k -- u_{k+1}, an x_0 -- x_N entry.
  auto addH = [&](int a, int b, double v) {
    q.p.hess_rows.push_back(std::max(a, b));
    q.p.hess_cols.push_back(std::min(a, b));
    q.hess.push_back(v);
  };
  for (int k = 0; k <= N; ++k) {
    const int n = k < N ? nx + nu : nx;
    for (int a = 0; a < n; ++a)
      for (int b = 0; b <= a; ++b) addH(k * (nx + nu) + a, k * (nx + nu) + b, (a == b ? (convex ? 2.0 : 0.0) : 0.3) * U(rng));
    if (k + 1 < N) addH(Uv(k, 0), Uv(k + 1, 0), -0.5);
  }
  addH(X(0, 2), X(N, 2), 0.2);
  q.dx.resize(q.p.n);
  for (int v = 0; v < q.p.n; ++v) q.dx[v] = convex ? 3.0 + std::abs(U(rng)) : 0.2 * U(rng);
  q.dc.resize(q.p.m);
  for (int r = 0; r < q.p.m; ++r) q.dc[r] = q.equality[r] ? delta_c : 0.5 + std::abs(U(rng));
  q.rx.resize(q.p.n);
  q.rc.resize(q.p.m);
  for (int v = 0; v < q.p.n; ++v) q.rx[v] = U(rng);
  for (int r = 0; r < q.p.m; ++r) q.rc[r] = U(rng);
  return q;
}

}  // namespace

TEST(StageKkt, SameStepAndMultipliersAsTheDenseSystem) {
  for (unsigned seed = 0; seed < 40; ++seed) {
    for (const double delta_c : {0.0, 1e-3}) {
      Problem q = randomProblem(seed, true, delta_c);
      StageKktSolver s(q.p, q.layout, q.fixed, q.equality);
      const DenseKkt d(q.p, q.fixed, s.alwaysExactRows(), q.hess.data(), q.jac.data(), q.dx, q.dc);
      ASSERT_EQ(s.factor(q.hess.data(), q.jac.data(), q.dx, q.dc), KktStatus::kOk) << "seed " << seed;
      Eigen::VectorXd dx, dy, rx, ry;
      s.solve(q.rx, q.rc, dx, dy);
      d.solve(q.rx, q.rc, rx, ry);
      // The structured solution satisfies the dense system to 1e-10 (relative residual) and agrees with the dense
      // solution to the conditioning of the instance.
      Eigen::VectorXd v(d.free_vars.size() + dy.size()), rhs(v.size());
      for (std::size_t i = 0; i < d.free_vars.size(); ++i) {
        v[static_cast<int>(i)] = dx[d.free_vars[i]];
        rhs[static_cast<int>(i)] = q.rx[d.free_vars[i]];
      }
      v.tail(dy.size()) = dy;
      rhs.tail(dy.size()) = q.rc;
      const double res = (d.K * v - rhs).cwiseAbs().maxCoeff() /
                         (d.K.cwiseAbs().maxCoeff() * v.cwiseAbs().maxCoeff() + rhs.cwiseAbs().maxCoeff());
      EXPECT_LT(res, 1e-10) << "seed " << seed << " delta_c " << delta_c;
      const double scale = 1.0 + rx.cwiseAbs().maxCoeff() + ry.cwiseAbs().maxCoeff();
      EXPECT_LT((dx - rx).cwiseAbs().maxCoeff() / scale, 1e-6) << "seed " << seed << " delta_c " << delta_c;
      EXPECT_LT((dy - ry).cwiseAbs().maxCoeff() / scale, 1e-6) << "seed " << seed << " delta_c " << delta_c;
      EXPECT_GT(s.carriedSize(q.layout.num_stages - 1), 0);  // x_0 carried to the end (periodicity)
    }
  }
}

TEST(StageKkt, PipelinedFillingGivesBitIdenticalFactorsAndSteps) {
  // The stage blocks filled on a second thread ahead of the recursion: the same status at every factorization
  // (also when the recursion stops early at an indefinite stage and the filling must still finish), and the same
  // step to the last bit. One solver object each, reused over all instances as the interior point reuses it.
  int early_stops = 0;
  for (unsigned seed = 0; seed < 40; ++seed) {
    Problem q = randomProblem(seed, seed % 2 == 0, seed % 3 == 0 ? 1e-3 : 0.0);
    StageKktSolver seq(q.p, q.layout, q.fixed, q.equality), pip(q.p, q.layout, q.fixed, q.equality);
    pip.setPipelined(true);
    for (int repeat = 0; repeat < 3; ++repeat) {
      const KktStatus a = seq.factor(q.hess.data(), q.jac.data(), q.dx, q.dc);
      const KktStatus b = pip.factor(q.hess.data(), q.jac.data(), q.dx, q.dc);
      ASSERT_EQ(a, b) << "seed " << seed;
      early_stops += a == KktStatus::kWrongInertia;
      if (a != KktStatus::kOk) continue;
      Eigen::VectorXd x1, y1, x2, y2;
      seq.solve(q.rx, q.rc, x1, y1);
      pip.solve(q.rx, q.rc, x2, y2);
      ASSERT_EQ(x1, x2) << "seed " << seed;
      ASSERT_EQ(y1, y2) << "seed " << seed;
    }
  }
  EXPECT_GT(early_stops, 0);
}

TEST(StageKkt, TwoSolvesInOnePassOrOnTwoThreadsGiveTheBitsOfOneAfterTheOther) {
  // solveTwo() runs the two recursions stage by stage in one pass over the factors, each with its own vectors, or,
  // with the pipelined factorization, each solve and its refinement on its own thread: each result is bit-identical
  // to a solve of its own on another solver, over repeated factorizations (the vectors are reused), with and
  // without a dual regularization.
  int solved = 0;
  for (unsigned seed = 0; seed < 40; ++seed) {
    Problem q = randomProblem(seed, true, seed % 3 == 0 ? 1e-3 : 0.0);
    StageKktSolver seq(q.p, q.layout, q.fixed, q.equality), pip(q.p, q.layout, q.fixed, q.equality);
    StageKktSolver one_pass(q.p, q.layout, q.fixed, q.equality);
    pip.setPipelined(true);
    std::mt19937 rng(seed + 1000);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    for (int repeat = 0; repeat < 3; ++repeat) {
      for (double& v : q.hess) v *= 1.0 + 0.01 * U(rng);
      const KktStatus st = seq.factor(q.hess.data(), q.jac.data(), q.dx, q.dc);
      ASSERT_EQ(st, pip.factor(q.hess.data(), q.jac.data(), q.dx, q.dc)) << "seed " << seed;
      ASSERT_EQ(st, one_pass.factor(q.hess.data(), q.jac.data(), q.dx, q.dc)) << "seed " << seed;
      if (st == KktStatus::kWrongInertia) continue;
      Eigen::VectorXd rx2(q.rx.size()), rc2(q.rc.size());
      for (int i = 0; i < rx2.size(); ++i) rx2[i] = U(rng);
      for (int r = 0; r < rc2.size(); ++r) rc2[r] = U(rng);
      Eigen::VectorXd x1, y1, x2, y2, a1, b1, a2, b2;
      seq.solve(q.rx, q.rc, x1, y1);
      seq.solve(rx2, rc2, x2, y2);
      for (StageKktSolver* two : {&pip, &one_pass}) {
        two->solveTwo({q.rx, q.rc, a1, b1}, {rx2, rc2, a2, b2});
        ASSERT_EQ(a1, x1) << "seed " << seed;
        ASSERT_EQ(b1, y1) << "seed " << seed;
        ASSERT_EQ(a2, x2) << "seed " << seed;
        ASSERT_EQ(b2, y2) << "seed " << seed;
        EXPECT_EQ(two->lastResidual(), seq.lastResidual()) << "seed " << seed;
      }
      ++solved;
    }
  }
  EXPECT_GT(solved, 60);
}

TEST(StageKkt, ARefactorizationGivesTheBitsOfAFreshSolver) {
  // The stage blocks are reused between factorizations and only partly reset (the dynamics where they can be
  // nonzero): a solver that factored other values first (other Jacobian values, some of them exactly zero, and
  // another dual regularization, which moves equality rows between the exact rows and the penalties) gives the
  // same bits as a fresh one.
  for (unsigned seed = 0; seed < 40; ++seed) {
    const double delta_c = seed % 2 == 0 ? 1e-3 : 0.0;
    const Problem q = randomProblem(seed, true, delta_c);
    Problem other = q;
    std::mt19937 rng(seed + 2000);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    for (std::size_t t = 0; t < other.jac.size(); ++t) other.jac[t] = t % 5 == 0 ? 0.0 : other.jac[t] * (1.0 + 0.5 * U(rng));
    for (int r = 0; r < other.dc.size(); ++r)
      if (q.equality[r]) other.dc[r] = delta_c > 0.0 ? 0.0 : 1e-3;
    StageKktSolver reused(q.p, q.layout, q.fixed, q.equality), fresh(q.p, q.layout, q.fixed, q.equality);
    reused.factor(other.hess.data(), other.jac.data(), other.dx, other.dc);
    const KktStatus st = reused.factor(q.hess.data(), q.jac.data(), q.dx, q.dc);
    ASSERT_EQ(st, fresh.factor(q.hess.data(), q.jac.data(), q.dx, q.dc)) << "seed " << seed;
    ASSERT_NE(st, KktStatus::kWrongInertia) << "seed " << seed;
    Eigen::VectorXd x1, y1, x2, y2;
    reused.solve(q.rx, q.rc, x1, y1);
    fresh.solve(q.rx, q.rc, x2, y2);
    ASSERT_EQ(x1, x2) << "seed " << seed;
    ASSERT_EQ(y1, y2) << "seed " << seed;
  }
}

TEST(StageKkt, ARetryOfTheInertiaCorrectionGivesTheBitsOfAFactorization) {
  // refactor() with the same Hessian and Jacobian and growing diagonals (the primal regularization and the slack
  // terms of the inequality rows, as the inertia correction tries them) keeps the rows of the last factorization,
  // also after it stopped early; with a dual regularization on the equality rows, which changes the exact rows, it
  // factors anew. Either way: the status, inertia and step of factor() on a fresh solver, to the last bit.
  int early_then_kept = 0, solved = 0;
  for (unsigned seed = 0; seed < 40; ++seed) {
    Problem q = randomProblem(seed, false, 0.0);
    StageKktSolver retry(q.p, q.layout, q.fixed, q.equality);
    retry.setPipelined(seed % 2 == 1);
    bool stopped = retry.factor(q.hess.data(), q.jac.data(), q.dx, q.dc) == KktStatus::kWrongInertia;
    const Eigen::VectorXd dx0 = q.dx, dc0 = q.dc;
    for (const double delta : {1e-2, 1.0, 8.0, 64.0, -1.0}) {
      if (delta < 0.0) {  // a dual regularization: the equality rows become penalties
        for (int r = 0; r < q.dc.size(); ++r)
          if (q.equality[r]) q.dc[r] = 1e-3;
      } else {
        q.dx = dx0.array() + delta;
        for (int r = 0; r < q.dc.size(); ++r)
          if (!q.equality[r]) q.dc[r] = 1.0 / (1.0 / dc0[r] + delta);
      }
      StageKktSolver fresh(q.p, q.layout, q.fixed, q.equality);
      const KktStatus a = retry.refactor(q.hess.data(), q.jac.data(), q.dx, q.dc);
      ASSERT_EQ(a, fresh.factor(q.hess.data(), q.jac.data(), q.dx, q.dc)) << "seed " << seed << " delta " << delta;
      EXPECT_EQ(retry.inertia().positive, fresh.inertia().positive) << "seed " << seed;
      early_then_kept += stopped && delta > 0.0;
      stopped = a == KktStatus::kWrongInertia;
      if (stopped) continue;
      Eigen::VectorXd x1, y1, x2, y2;
      retry.solve(q.rx, q.rc, x1, y1);
      fresh.solve(q.rx, q.rc, x2, y2);
      ASSERT_EQ(x1, x2) << "seed " << seed << " delta " << delta;
      ASSERT_EQ(y1, y2) << "seed " << seed << " delta " << delta;
      ++solved;
    }
  }
  EXPECT_GT(early_then_kept, 5);
  EXPECT_GT(solved, 80);
}

// The relative residual of the system for (dx, dy), written as plain loops over the triplets: r = rhs - K [dx; dy]
// (the fixed variables' rows zero), divided by max(|rhs|, |K| |[dx; dy]|).
double plainResidual(const Problem& q, const std::vector<char>& exact_rows, const Eigen::VectorXd& dx,
                     const Eigen::VectorXd& dy) {
  Eigen::VectorXd rx = q.rx, rc = q.rc;
  for (std::size_t t = 0; t < q.hess.size(); ++t) {
    const int a = q.p.hess_rows[t], b = q.p.hess_cols[t];
    rx[a] -= q.hess[t] * dx[b];
    if (a != b) rx[b] -= q.hess[t] * dx[a];
  }
  for (int v = 0; v < q.p.n; ++v) rx[v] -= q.dx[v] * dx[v];
  for (std::size_t t = 0; t < q.jac.size(); ++t) {
    rx[q.p.jac_cols[t]] -= q.jac[t] * dy[q.p.jac_rows[t]];
    rc[q.p.jac_rows[t]] -= q.jac[t] * dx[q.p.jac_cols[t]];
  }
  for (int r = 0; r < q.p.m; ++r)
    if (!exact_rows[r]) rc[r] += q.dc[r] * dy[r];
  for (int v = 0; v < q.p.n; ++v)
    if (q.fixed[v]) rx[v] = 0.0;
  double kmax = q.dx.cwiseAbs().maxCoeff();
  for (double h : q.hess) kmax = std::max(kmax, std::abs(h));
  for (double j : q.jac) kmax = std::max(kmax, std::abs(j));
  const double sol = std::max(dx.cwiseAbs().maxCoeff(), dy.cwiseAbs().maxCoeff());
  const double scale = std::max({q.rx.cwiseAbs().maxCoeff(), q.rc.cwiseAbs().maxCoeff(), kmax * sol, 1e-300});
  return std::max(rx.cwiseAbs().maxCoeff(), rc.cwiseAbs().maxCoeff()) / scale;
}

// The refinement's residual (what lastResidual() reports for the returned step) is the plain one, bit for bit, on
// patterns whose triplets are not sorted by row.
TEST(StageKkt, TheReportedResidualIsThePlainResidualOfTheStep) {
  int nonzero = 0;
  for (unsigned seed = 0; seed < 40; ++seed) {
    for (const double delta_c : {0.0, 1e-3}) {
      Problem q = randomProblem(seed, true, delta_c);
      StageKktSolver s(q.p, q.layout, q.fixed, q.equality);
      s.max_refinement = 0;  // report the residual of the first solve (refinement usually leaves ~1e-16)
      ASSERT_EQ(s.factor(q.hess.data(), q.jac.data(), q.dx, q.dc), KktStatus::kOk) << "seed " << seed;
      Eigen::VectorXd dx, dy;
      s.solve(q.rx, q.rc, dx, dy);
      EXPECT_EQ(s.lastResidual(), plainResidual(q, s.alwaysExactRows(), dx, dy)) << "seed " << seed;
      nonzero += s.lastResidual() > 0.0;
    }
  }
  EXPECT_GT(nonzero, 60);  // the comparison is not between zeros
}

TEST(StageKkt, WrongInertiaExactlyWhenTheDenseMatrixHasIt) {
  int wrong = 0;
  for (unsigned seed = 50; seed < 120; ++seed) {
    Problem q = randomProblem(seed, false, 0.0);
    StageKktSolver s(q.p, q.layout, q.fixed, q.equality);
    const DenseKkt d(q.p, q.fixed, s.alwaysExactRows(), q.hess.data(), q.jac.data(), q.dx, q.dc);
    const Inertia in = d.inertia();
    if (in.zero > 0) continue;
    const int nf = static_cast<int>(d.free_vars.size());
    const bool correct = in.positive == nf && in.negative == q.p.m;
    const KktStatus st = s.factor(q.hess.data(), q.jac.data(), q.dx, q.dc);
    EXPECT_EQ(st == KktStatus::kOk, correct) << "seed " << seed;
    wrong += !correct;
  }
  EXPECT_GT(wrong, 5);
}

TEST(StageKkt, RefusesAStateWithoutDynamics) {
  Problem q = randomProblem(1, true, 0.0);
  // Drop the entry on x_1[0] of its dynamics row: x_1[0] then has no dynamics row.
  for (std::size_t t = 0; t < q.p.jac_rows.size(); ++t) {
    if (q.p.jac_cols[t] == 5) q.p.jac_cols[t] = 0;
  }
  EXPECT_THROW(StageKktSolver(q.p, q.layout, q.fixed, q.equality), StructureError);
}
