// ctest-labels: unit
// The dense QP solver never answers "optimal" wrongly: singular (positive semidefinite) Hessians, unbounded
// problems and ill-conditioned Hessians, on problems whose answer is known by construction or given by Ipopt.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "qp/qp_solver.hpp"
#include "random_qp.hpp"

using centaur::QpSolver;
using centaur::QpStatus;
using centaur::test::DenseQp;
using centaur::test::KnownQp;
using centaur::test::kktResidual;
using centaur::test::solveQp;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {
double maxAbs(const VectorXd& v) { return v.size() > 0 ? v.cwiseAbs().maxCoeff() : 0.0; }

QpSolver sizedFor(const DenseQp& qp) {
  return QpSolver(qp.n(), static_cast<int>(qp.A_eq.rows()), static_cast<int>(qp.C.rows()));
}
}  // namespace

TEST(QpSemidefinite, RankDeficientHessianGivesTheKnownAnswer) {
  // H of rank r < n (r = 0: a linear program); the active constraints pin the null space of H, so the optimum
  // x* and its multipliers are unique and known. Whether the Cholesky factorisation of such an H fails or
  // succeeds by rounding, the answer is x*.
  std::mt19937 rng(151);
  int worst_trial = -1;
  double worst = 0.0;
  for (int trial = 0; trial < 400; ++trial) {
    const int n = std::uniform_int_distribution<int>(1, 30)(rng);
    const int r = std::uniform_int_distribution<int>(0, n - 1)(rng);
    const KnownQp k = centaur::test::knownAnswer(rng, n, r);
    QpSolver s = sizedFor(k.qp);
    ASSERT_EQ(solveQp(s, k.qp), QpStatus::kOptimal) << "trial " << trial << " n " << n << " rank " << r;
    const double err = maxAbs(s.x() - k.x) / (1.0 + maxAbs(k.x));
    if (err > worst) worst = err, worst_trial = trial;
    EXPECT_LT(err, 1e-7) << "trial " << trial << " n " << n << " rank " << r;
    EXPECT_NEAR(s.objective(), k.objective, 1e-8 * (1.0 + std::abs(k.objective))) << "trial " << trial;
    EXPECT_LT(maxAbs(s.yIneq() - k.y_in), 1e-6 * (1.0 + maxAbs(k.y_in))) << "trial " << trial;
    EXPECT_LT(maxAbs(s.yEq() - k.y_eq), 1e-6 * (1.0 + maxAbs(k.y_eq))) << "trial " << trial;
    if (k.y_box.size() > 0) {
      EXPECT_LT(maxAbs(s.yBox() - k.y_box), 1e-6 * (1.0 + maxAbs(k.y_box))) << "trial " << trial;
    }
  }
  std::printf("worst relative error of x: %.3g (trial %d)\n", worst, worst_trial);
}

TEST(QpSemidefinite, UnboundedProblemsAreReportedWithARay) {
  // f(x0 + t d) = f(x0) + t g'd with g'd < 0 along a feasible ray d of the null space of H: no optimum. The
  // solver says so and returns a ray of its own: flat (H d = 0), descending (g'd < 0), feasible from x().
  std::mt19937 rng(152);
  int max_prox = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const int n = std::uniform_int_distribution<int>(1, 30)(rng);
    const int r = std::uniform_int_distribution<int>(0, n - 1)(rng);
    const DenseQp qp = centaur::test::unboundedQp(rng, n, r, false);
    QpSolver s = sizedFor(qp);
    ASSERT_EQ(solveQp(s, qp), QpStatus::kUnbounded) << "trial " << trial << " n " << n << " rank " << r;
    max_prox = std::max(max_prox, s.proximalIterations());
    const VectorXd d = s.ray();
    EXPECT_NEAR(d.norm(), 1.0, 1e-12);
    EXPECT_LT((qp.H * d).norm(), 1e-9 * qp.H.norm() + 1e-12) << "trial " << trial;
    EXPECT_LT(qp.g.dot(d), -1e-6 * qp.g.norm()) << "trial " << trial;
    const VectorXd x = s.x();  // a feasible point (to the rounding of n'x, which grows with ||n|| ||x||)
    const double x_max = x.cwiseAbs().maxCoeff();
    for (int i = 0; i < qp.A_eq.rows(); ++i) {
      const double a = qp.A_eq.row(i).norm();
      EXPECT_NEAR(qp.A_eq.row(i).dot(d), 0.0, 1e-9 * a) << "trial " << trial;
      EXPECT_NEAR(qp.A_eq.row(i).dot(x), qp.b_eq[i], 1e-9 * std::max({1.0, std::abs(qp.b_eq[i]), a * x_max}))
          << "trial " << trial;
    }
    // x + t d feasible for a large t (rows along which d runs keep their rounding-level slope)
    const double t = 1e3;
    const VectorXd c0 = qp.C * x, c1 = qp.C * (x + t * d);
    for (int i = 0; i < qp.C.rows(); ++i) {
      const double tol = 1e-9 * std::max(1.0, (x_max + t) * qp.C.row(i).norm());
      EXPECT_GE(std::min(c0[i], c1[i]), qp.c_lo[i] - tol) << "trial " << trial << " row " << i;
      EXPECT_LE(std::max(c0[i], c1[i]), qp.c_up[i] + tol) << "trial " << trial << " row " << i;
    }
    if (qp.x_lo.size() > 0) {
      const VectorXd x1 = x + t * d;
      const double tol = 1e-9 * std::max(1.0, x_max + t);
      EXPECT_TRUE((x1.array() >= qp.x_lo.array() - tol).all() && (x1.array() <= qp.x_up.array() + tol).all());
      EXPECT_TRUE((x.array() >= qp.x_lo.array() - tol).all() && (x.array() <= qp.x_up.array() + tol).all());
    }
  }
  std::printf("most proximal iterations: %d\n", max_prox);
}

TEST(QpSemidefinite, BlockedRaysGiveTheIpoptAnswer) {
  // The same problems with every null-space direction of H bounded by two-sided rows: an optimum exists.
  std::mt19937 rng(153);
  int compared = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const int n = std::uniform_int_distribution<int>(1, 25)(rng);
    const int r = std::uniform_int_distribution<int>(0, n - 1)(rng);
    const DenseQp qp = centaur::test::unboundedQp(rng, n, r, true);
    QpSolver s = sizedFor(qp);
    ASSERT_EQ(solveQp(s, qp), QpStatus::kOptimal) << "trial " << trial << " n " << n << " rank " << r;
    EXPECT_LT(kktResidual(qp, s), 1e-9) << "trial " << trial;
    const auto oracle = centaur::test::solveWithIpopt(qp);
    VectorXd xp;
    if (oracle.x.size() != n || !centaur::test::polishOnActiveSet(qp, oracle.x, xp)) continue;
    ++compared;
    const double f = qp.objective(xp);
    EXPECT_NEAR(s.objective(), f, 1e-8 * std::max(1.0, std::abs(f))) << "trial " << trial;
  }
  EXPECT_GE(compared, 150);
}

TEST(QpSemidefinite, IllConditionedHessiansAgainstIpopt) {
  // H = M'M (rank n/2) + rel_reg * max(H_ii) * I: positive definite, condition number ~ 1 / rel_reg; g either
  // in the range of M' (a regularised least-squares cost, as in the whole-body stack: the optimum stays bounded as
  // rel_reg -> 0) or random (|x*| grows like 1 / rel_reg). An answer reported optimal satisfies the KKT conditions
  // (relative to the rounding of its terms) and has Ipopt's objective (Ipopt's answer polished on its active set).
  // Below rel_reg = 1e-10 (singular_tol) the proximal iterations take over (the range the stack YAML and the force
  // distribution accept stays far above it, docs/qp.md).
  std::mt19937 rng(154);
  QpSolver s(30, 32, 60);
  for (const bool least_squares : {true, false}) {
    for (double rel_reg : {1e-4, 1e-6, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13, 0.0}) {
      const int trials = 40;
      int optimal = 0, compared = 0, prox = 0;
      int count[7] = {0, 0, 0, 0, 0, 0, 0};
      double worst_obj = 0.0, worst_kkt = 0.0;
      for (int trial = 0; trial < trials; ++trial) {
        const DenseQp qp = centaur::test::randomFeasible(rng, 30, rel_reg, least_squares);
        const QpStatus st = solveQp(s, qp);
        ++count[static_cast<int>(st)];
        // Feasible and convex by construction: never infeasible nor "not convex"; a least-squares cost is bounded
        // below, so its problems are always solved; a random g may make a flat direction descend (unbounded).
        if (least_squares) {
          EXPECT_EQ(st, QpStatus::kOptimal) << "rel_reg " << rel_reg << " trial " << trial;
        } else {
          EXPECT_TRUE(st == QpStatus::kOptimal || st == QpStatus::kUnbounded)
              << "rel_reg " << rel_reg << " trial " << trial << ": " << centaur::toString(st);
        }
        if (st != QpStatus::kOptimal) continue;
        ++optimal;
        prox += s.proximalIterations() > 0;
        const double kkt = centaur::test::kktResidualRelative(qp, s);
        worst_kkt = std::max(worst_kkt, kkt);
        EXPECT_LT(kkt, 1e-8) << "rel_reg " << rel_reg << " trial " << trial;
        const auto oracle = centaur::test::solveWithIpopt(qp);
        VectorXd xp;
        if (oracle.x.size() != qp.n() || !centaur::test::polishOnActiveSet(qp, oracle.x, xp)) continue;
        ++compared;
        const double f = qp.objective(xp);
        const double rel = std::abs(s.objective() - f) / std::max(1.0, std::abs(f));
        worst_obj = std::max(worst_obj, rel);
        EXPECT_LT(rel, 1e-8) << "rel_reg " << rel_reg << " trial " << trial;
      }
      std::printf("%s g, relative regularisation %.0e: %d / %d optimal (%d by proximal iterations), %d compared with "
                  "Ipopt, worst objective difference %.2g, worst relative KKT residual %.2g; statuses",
                  least_squares ? "least-squares" : "random", rel_reg, optimal, trials, prox, compared, worst_obj,
                  worst_kkt);
      for (int c : count) std::printf(" %d", c);
      std::printf("\n");
    }
  }
}

TEST(QpSemidefinite, AFarBoundAlongAFlatDirectionIsReachedNotCalledUnbounded) {
  // min 1/2 x1^2 - x2: flat and descending along x2, blocked far away. By a bound x2 <= 1e9: the optimum (0, 1e9),
  // multiplier -1; by a row 0.3 x1 + x2 <= 1e8: x1 = -0.3, x2 = 1e8 + 0.09, multiplier -1. The proximal steps
  // (|g| / rho = 1e7 each) would need ~100 iterations to creep there: they jump to the blocking bound instead.
  const double kInf = centaur::test::kInf;
  const MatrixXd H = Eigen::Vector2d(1.0, 0.0).asDiagonal();
  const Eigen::Vector2d g(0.0, -1.0);
  const MatrixXd none(0, 2);
  const VectorXd e0(0);
  QpSolver s(2, 0, 1);
  ASSERT_EQ(s.solve(H, g, none, e0, none, e0, e0, Eigen::Vector2d(-1.0, -kInf), Eigen::Vector2d(1.0, 1e9)),
            QpStatus::kOptimal);
  EXPECT_NEAR(s.x()[0], 0.0, 1e-9);
  EXPECT_NEAR(s.x()[1], 1e9, 1e-9 * 1e9);
  EXPECT_NEAR(s.yBox()[1], -1.0, 1e-9);
  EXPECT_NEAR(s.objective(), -1e9, 1e-9 * 1e9);
  EXPECT_LE(s.proximalIterations(), 4);
  const MatrixXd row = (MatrixXd(1, 2) << 0.3, 1.0).finished();
  ASSERT_EQ(s.solve(H, g, none, e0, row, VectorXd::Constant(1, -kInf), VectorXd::Constant(1, 1e8), e0, e0),
            QpStatus::kOptimal);
  EXPECT_NEAR(s.x()[0], -0.3, 1e-6);
  EXPECT_NEAR(s.x()[1], 1e8 + 0.09, 1e-9 * 1e8);
  EXPECT_NEAR(s.yIneq()[0], -1.0, 1e-9);
  EXPECT_LE(s.proximalIterations(), 4);
}

TEST(QpSemidefinite, EveryStatusIsReachable) {
  // One small problem per status, each with the answer it must give.
  QpSolver s(2, 1, 2);
  const MatrixXd none(0, 2);
  const VectorXd e0(0);
  const double kInf = centaur::test::kInf;
  auto solve = [&](const MatrixXd& H, const VectorXd& g, const MatrixXd& C, const VectorXd& lo, const VectorXd& up,
                   const VectorXd& xl = VectorXd(), const VectorXd& xu = VectorXd()) {
    return s.solve(H, g, none, e0, C, lo, up, xl, xu);
  };
  const MatrixXd I = MatrixXd::Identity(2, 2);
  const MatrixXd row = (MatrixXd(1, 2) << 1.0, 1.0).finished();
  // optimal: min 1/2 |x|^2 - (1, 1)'x s.t. x1 + x2 <= 1 -> x = (0.5, 0.5), y = -0.5 (upper side)
  ASSERT_EQ(solve(I, -VectorXd::Ones(2), row, VectorXd::Constant(1, -kInf), VectorXd::Ones(1)), QpStatus::kOptimal);
  EXPECT_NEAR(s.x()[0], 0.5, 1e-15);
  EXPECT_NEAR(s.yIneq()[0], -0.5, 1e-15);
  // infeasible: x1 + x2 >= 1 and x1 + x2 <= -1 (two rows)
  const MatrixXd rows = (MatrixXd(2, 2) << 1.0, 1.0, 1.0, 1.0).finished();
  EXPECT_EQ(solve(I, VectorXd::Zero(2), rows, Eigen::Vector2d(1.0, -kInf), Eigen::Vector2d(kInf, -1.0)),
            QpStatus::kInfeasible);
  // invalid input: NaN in g
  EXPECT_EQ(solve(I, Eigen::Vector2d(0.0, std::nan("")), none, e0, e0), QpStatus::kInvalidInput);
  // not convex: an eigenvalue -1
  EXPECT_EQ(solve(Eigen::Vector2d(1.0, -1.0).asDiagonal().toDenseMatrix(), VectorXd::Zero(2), none, e0, e0),
            QpStatus::kNotPositiveDefinite);
  // unbounded: H = diag(1, 0), g = (0, -1), x1 in [-1, 1]: f -> -inf along the ray (0, 1)
  const MatrixXd Hs = Eigen::Vector2d(1.0, 0.0).asDiagonal();
  ASSERT_EQ(solve(Hs, Eigen::Vector2d(0.0, -1.0), none, e0, e0, Eigen::Vector2d(-1.0, -kInf),
                  Eigen::Vector2d(1.0, kInf)),
            QpStatus::kUnbounded);
  EXPECT_NEAR(s.ray()[0], 0.0, 1e-12);
  EXPECT_NEAR(s.ray()[1], 1.0, 1e-12);
  // the same bounded by x2 <= 3: optimal at (0, 3) with the bound's multiplier -1, by proximal iterations
  ASSERT_EQ(solve(Hs, Eigen::Vector2d(0.0, -1.0), none, e0, e0, Eigen::Vector2d(-1.0, -kInf),
                  Eigen::Vector2d(1.0, 3.0)),
            QpStatus::kOptimal);
  EXPECT_NEAR(s.x()[0], 0.0, 1e-12);
  EXPECT_NEAR(s.x()[1], 3.0, 1e-12);
  EXPECT_NEAR(s.yBox()[1], -1.0, 1e-12);
  EXPECT_GT(s.proximalIterations(), 0);
  // iteration limit: of the proximal iterations (the unbounded problem needs two to show its ray) ...
  s.settings().max_proximal_iterations = 1;
  EXPECT_EQ(solve(Hs, Eigen::Vector2d(0.0, -1.0), none, e0, e0, Eigen::Vector2d(-1.0, -kInf),
                  Eigen::Vector2d(1.0, kInf)),
            QpStatus::kIterationLimit);
  s.settings() = centaur::QpSettings();
  // (a linear program: H = 0, max x1 + 2 x2 s.t. x1 + x2 <= 1, x >= 0, at its vertex (0, 1))
  ASSERT_EQ(solve(MatrixXd::Zero(2, 2), Eigen::Vector2d(-1.0, -2.0), row, VectorXd::Constant(1, -kInf),
                  VectorXd::Ones(1), Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(kInf, kInf)),
            QpStatus::kOptimal);
  EXPECT_NEAR(s.x()[0], 0.0, 1e-12);
  EXPECT_NEAR(s.x()[1], 1.0, 1e-12);
  EXPECT_NEAR(s.objective(), -2.0, 1e-12);
  // ... and of the active-set changes
  s.settings().max_iterations = 1;
  s.resetWarmStart();
  EXPECT_EQ(solve(I, Eigen::Vector2d(-3.0, -3.0), rows, Eigen::Vector2d(-kInf, -kInf), Eigen::Vector2d(1.0, 1.0),
                  Eigen::Vector2d(2.0, -kInf), Eigen::Vector2d(kInf, kInf)),
            QpStatus::kIterationLimit);
  // inaccurate: a KKT tolerance below the rounding of the data cannot be met by the direct answer nor by the
  // proximal iterations; the answer is not reported optimal
  std::mt19937 rng(155);
  const KnownQp k = centaur::test::knownAnswer(rng, 10, 10);
  QpSolver strict = sizedFor(k.qp);
  ASSERT_EQ(solveQp(strict, k.qp), QpStatus::kOptimal);
  strict.settings().kkt_tol = 1e-30;
  EXPECT_EQ(solveQp(strict, k.qp), QpStatus::kInaccurate);
  // distinct names for messages
  std::vector<std::string> names;
  for (int k = 0; k <= static_cast<int>(QpStatus::kInaccurate); ++k) {
    names.push_back(centaur::toString(static_cast<QpStatus>(k)));
    EXPECT_NE(names.back(), "unknown");
  }
  std::sort(names.begin(), names.end());
  EXPECT_EQ(std::unique(names.begin(), names.end()), names.end());
}
