// ctest-labels: unit
// Dense QP solver (Goldfarb-Idnani) against Ipopt as an oracle on random feasible problems with degenerate
// cases, infeasible problems, warm start, analytic answers and invalid input.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "qp/qp_solver.hpp"
#include "random_qp.hpp"

using centaur::QpSolver;
using centaur::QpStatus;
using centaur::test::DenseQp;
using Eigen::MatrixXd;
using Eigen::VectorXd;

using centaur::test::kktResidual;
using centaur::test::randomFeasible;
using centaur::test::solveQp;
constexpr double kInf = centaur::test::kInf;

TEST(QpSolver, UnconstrainedAndBoxAnalytic) {
  // min 1/2 ||x||^2 - a'x, box [0, 1]: x = clamp(a), multipliers y_box = x - a.
  DenseQp qp;
  qp.H = MatrixXd::Identity(3, 3);
  qp.g.resize(3);
  qp.g << -2.0, 1.0, -0.5;
  qp.A_eq.resize(0, 3);
  qp.b_eq.resize(0);
  qp.C.resize(0, 3);
  qp.c_lo.resize(0);
  qp.c_up.resize(0);
  qp.x_lo = VectorXd::Zero(3);
  qp.x_up = VectorXd::Ones(3);
  QpSolver s(3, 0, 0);
  ASSERT_EQ(solveQp(s, qp), QpStatus::kOptimal);
  EXPECT_NEAR(s.x()[0], 1.0, 1e-14);
  EXPECT_NEAR(s.x()[1], 0.0, 1e-14);
  EXPECT_NEAR(s.x()[2], 0.5, 1e-14);
  EXPECT_NEAR(s.yBox()[0], -1.0, 1e-14);  // upper bound active: y <= 0
  EXPECT_NEAR(s.yBox()[1], 1.0, 1e-14);   // lower bound active: y >= 0
  EXPECT_NEAR(s.yBox()[2], 0.0, 1e-14);
}

TEST(QpSolver, EqualityConstrainedLeastNorm) {
  // min 1/2 ||x||^2 s.t. sum(x) = 1 -> x = 1/n, y = 1/n; a duplicated (redundant) equality is accepted.
  const int n = 4;
  DenseQp qp;
  qp.H = MatrixXd::Identity(n, n);
  qp.g = VectorXd::Zero(n);
  qp.A_eq = MatrixXd::Ones(2, n);
  qp.b_eq = VectorXd::Ones(2);
  qp.C.resize(0, n);
  qp.c_lo.resize(0);
  qp.c_up.resize(0);
  QpSolver s(n, 2, 0);
  ASSERT_EQ(solveQp(s, qp), QpStatus::kOptimal);
  for (int j = 0; j < n; ++j) EXPECT_NEAR(s.x()[j], 0.25, 1e-14);
  EXPECT_NEAR(s.yEq().sum(), 0.25, 1e-14);
  EXPECT_NEAR(s.objective(), 0.125, 1e-14);
}

TEST(QpSolver, AgreesWithIpoptOnRandomFeasibleProblems) {
  std::mt19937 rng(20261122);
  int compared = 0, oracle_failed = 0, polished = 0;
  double worst_obj = 0.0, worst_kkt = 0.0;
  // One solver sized once for the largest problem solves every smaller one (and its warm start, taken from an
  // unrelated previous problem, must not change the answer).
  QpSolver s(45, 47, 90);
  for (int trial = 0; trial < 1100; ++trial) {
    const DenseQp qp = randomFeasible(rng, trial < 1000 ? 25 : 45);
    const QpStatus st = solveQp(s, qp);
    ASSERT_EQ(st, QpStatus::kOptimal) << "trial " << trial;
    const double kkt = kktResidual(qp, s);
    worst_kkt = std::max(worst_kkt, kkt);
    EXPECT_LT(kkt, 1e-9) << "trial " << trial << " n " << qp.n();
    EXPECT_NEAR(s.objective(), qp.objective(s.x()), 1e-10 * (1.0 + std::abs(s.objective())));
    // Oracle: Ipopt's answer, polished on the active set it identifies (a certified optimum when the polished
    // point is feasible with correctly signed multipliers; Ipopt alone is only accurate to ~1e-6 on the
    // degenerate, ill-conditioned cases).
    const auto oracle = centaur::test::solveWithIpopt(qp);
    if (oracle.x.size() != qp.n()) {
      ++oracle_failed;
      continue;
    }
    VectorXd x_polished;
    double oracle_objective = oracle.objective;
    if (centaur::test::polishOnActiveSet(qp, oracle.x, x_polished)) {
      oracle_objective = qp.objective(x_polished);
      ++polished;
    } else if (!oracle.solved) {
      ++oracle_failed;
      continue;
    }
    ++compared;
    const double rel = std::abs(oracle_objective - s.objective()) / std::max(1.0, std::abs(oracle_objective));
    worst_obj = std::max(worst_obj, rel);
    EXPECT_LT(rel, 1e-8) << "trial " << trial << " ours " << s.objective() << " oracle " << oracle_objective
                         << " ipopt raw " << oracle.objective << " status " << oracle.status;
  }
  std::printf("compared %d problems with Ipopt (%d polished on the active set, %d oracle failures); worst relative "
              "objective difference %.3g, worst KKT residual %.3g\n",
              compared, polished, oracle_failed, worst_obj, worst_kkt);
  EXPECT_GE(compared, 1000);
}

TEST(QpSolver, ReportsInfeasibleProblems) {
  std::mt19937 rng(7);
  std::normal_distribution<double> N(0.0, 1.0);
  QpSolver s;
  for (int trial = 0; trial < 200; ++trial) {
    DenseQp qp = randomFeasible(rng, 15);
    const int n = qp.n();
    const int kind = trial % 4;
    VectorXd a(n);
    for (int j = 0; j < n; ++j) a[j] = N(rng);
    if (kind == 0) {  // inconsistent duplicated equality
      qp.A_eq.conservativeResize(qp.A_eq.rows() + 2, n);
      qp.b_eq.conservativeResize(qp.b_eq.size() + 2);
      qp.A_eq.row(qp.A_eq.rows() - 2) = a.transpose();
      qp.A_eq.row(qp.A_eq.rows() - 1) = 2.0 * a.transpose();
      qp.b_eq.tail(2) << 1.0, 2.0 + 0.1;
    } else {  // two inequality rows a'x >= 1 and a'x <= -1 (kind 2: via -a'x >= 1), or box vs. a row
      const int extra = 2;
      const int m = static_cast<int>(qp.C.rows());
      qp.C.conservativeResize(m + extra, n);
      qp.c_lo.conservativeResize(m + extra);
      qp.c_up.conservativeResize(m + extra);
      if (kind == 3) {
        qp.x_lo = VectorXd::Constant(n, -1.0);
        qp.x_up = VectorXd::Constant(n, 1.0);
        qp.C.row(m) = VectorXd::Ones(n).transpose();
        qp.c_lo[m] = n + 0.5;
        qp.c_up[m] = kInf;
        qp.C.row(m + 1) = a.transpose();
        qp.c_lo[m + 1] = -kInf;
        qp.c_up[m + 1] = kInf;
      } else {
        qp.C.row(m) = a.transpose();
        qp.c_lo[m] = 1.0;
        qp.c_up[m] = kInf;
        qp.C.row(m + 1) = (kind == 1 ? 1.0 : -3.0) * a.transpose();
        qp.c_lo[m + 1] = kind == 1 ? -kInf : 3.0;
        qp.c_up[m + 1] = kind == 1 ? -1.0 : kInf;
      }
    }
    s.resize(n, static_cast<int>(qp.A_eq.rows()), static_cast<int>(qp.C.rows()));
    EXPECT_EQ(solveQp(s, qp), QpStatus::kInfeasible) << "trial " << trial << " kind " << kind;
  }
  // Crossed bounds are infeasible, too.
  DenseQp qp;
  qp.H = MatrixXd::Identity(2, 2);
  qp.g = VectorXd::Zero(2);
  qp.A_eq.resize(0, 2);
  qp.b_eq.resize(0);
  qp.C = MatrixXd::Ones(1, 2);
  qp.c_lo = VectorXd::Constant(1, 1.0);
  qp.c_up = VectorXd::Constant(1, 0.0);
  s.resize(2, 0, 1);
  EXPECT_EQ(solveQp(s, qp), QpStatus::kInfeasible);
}

TEST(QpSolver, WarmStartNeverChangesTheAnswer) {
  std::mt19937 rng(99);
  std::normal_distribution<double> N(0.0, 1.0);
  QpSolver warm, cold;
  cold.settings().warm_start = false;
  for (int trial = 0; trial < 100; ++trial) {
    DenseQp qp = randomFeasible(rng, 30);
    warm.resize(qp.n(), static_cast<int>(qp.A_eq.rows()), static_cast<int>(qp.C.rows()));
    cold.resize(qp.n(), static_cast<int>(qp.A_eq.rows()), static_cast<int>(qp.C.rows()));
    // A sequence of perturbed problems (like successive control ticks): g, bounds and rhs drift.
    for (int step = 0; step < 10; ++step) {
      if (step > 0) {
        for (int j = 0; j < qp.n(); ++j) qp.g[j] += 0.3 * N(rng);
        for (int i = 0; i < qp.C.rows(); ++i) {
          const double shift = 0.05 * N(rng);
          qp.c_lo[i] += shift;
          qp.c_up[i] += shift;
          if (qp.c_lo[i] > qp.c_up[i]) qp.c_lo[i] = qp.c_up[i];
        }
      }
      const QpStatus sw = solveQp(warm, qp);
      const QpStatus sc = solveQp(cold, qp);
      ASSERT_EQ(sw, sc) << "trial " << trial << " step " << step;
      if (sc != QpStatus::kOptimal) break;  // the drift may make a problem infeasible: both agree
      EXPECT_LT((warm.x() - cold.x()).norm(), 1e-8 * (1.0 + cold.x().norm())) << trial << " " << step;
      EXPECT_NEAR(warm.objective(), cold.objective(), 1e-9 * (1.0 + std::abs(cold.objective())));
      EXPECT_LT(kktResidual(qp, warm), 1e-9);
    }
  }
}

TEST(QpSolver, WarmStartSavesIterations) {
  std::mt19937 rng(5);
  DenseQp qp;
  do {
    qp = randomFeasible(rng, 40);
  } while (qp.n() < 30 || qp.C.rows() < 30);
  QpSolver s(qp.n(), static_cast<int>(qp.A_eq.rows()), static_cast<int>(qp.C.rows()));
  ASSERT_EQ(solveQp(s, qp), QpStatus::kOptimal);
  const int cold_iterations = s.iterations();
  const VectorXd x = s.x();
  ASSERT_EQ(solveQp(s, qp), QpStatus::kOptimal);
  EXPECT_EQ(s.iterations(), 0);  // the re-imposed active set is already optimal
  EXPECT_GT(cold_iterations, 0);
  EXPECT_LT((s.x() - x).norm(), 1e-10);
}

TEST(QpSolver, InvalidInputAndNonConvexAreReported) {
  DenseQp qp;
  qp.H = MatrixXd::Identity(2, 2);
  qp.g = VectorXd::Zero(2);
  qp.A_eq.resize(0, 2);
  qp.b_eq.resize(0);
  qp.C = MatrixXd::Ones(1, 2);
  qp.c_lo = VectorXd::Constant(1, -1.0);
  qp.c_up = VectorXd::Constant(1, 1.0);
  QpSolver s(2, 0, 1);
  ASSERT_EQ(solveQp(s, qp), QpStatus::kOptimal);
  DenseQp bad = qp;
  bad.g[1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(solveQp(s, bad), QpStatus::kInvalidInput);
  bad = qp;
  bad.c_lo[0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(solveQp(s, bad), QpStatus::kInvalidInput);
  bad = qp;
  bad.C(0, 0) = kInf;
  EXPECT_EQ(solveQp(s, bad), QpStatus::kInvalidInput);
  bad = qp;
  bad.H(1, 1) = -1.0;
  EXPECT_EQ(solveQp(s, bad), QpStatus::kNotPositiveDefinite);
  bad = qp;
  bad.C = MatrixXd::Ones(2, 2);  // more rows than resize() allowed
  bad.c_lo = VectorXd::Zero(2);
  bad.c_up = VectorXd::Ones(2);
  EXPECT_EQ(solveQp(s, bad), QpStatus::kInvalidInput);
  EXPECT_STREQ(centaur::toString(QpStatus::kInfeasible), "infeasible");
}

TEST(QpSolver, IterationLimitIsReported) {
  std::mt19937 rng(3);
  DenseQp qp;
  QpSolver s;
  for (;;) {
    qp = randomFeasible(rng, 30);
    s.resize(qp.n(), static_cast<int>(qp.A_eq.rows()), static_cast<int>(qp.C.rows()));
    s.settings().max_iterations = 0;
    ASSERT_EQ(solveQp(s, qp), QpStatus::kOptimal);
    if (s.iterations() >= 3) break;
  }
  s.resetWarmStart();
  s.settings().max_iterations = 1;
  EXPECT_EQ(solveQp(s, qp), QpStatus::kIterationLimit);
}
