// ctest-labels: unit
// The dense QP solver never answers "optimal" wrongly: singular (positive semidefinite) Hessians, unbounded
// problems and ill-conditioned Hessians, on problems whose answer is known by construction or given by Ipopt.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

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
    const double err = (s.x() - k.x).cwiseAbs().maxCoeff() / (1.0 + k.x.cwiseAbs().maxCoeff());
    if (err > worst) worst = err, worst_trial = trial;
    EXPECT_LT(err, 1e-7) << "trial " << trial << " n " << n << " rank " << r;
    EXPECT_NEAR(s.objective(), k.objective, 1e-8 * (1.0 + std::abs(k.objective))) << "trial " << trial;
    EXPECT_LT((s.yIneq() - k.y_in).cwiseAbs().maxCoeff(), 1e-6 * (1.0 + k.y_in.cwiseAbs().maxCoeff()))
        << "trial " << trial;
    EXPECT_LT((s.yEq() - k.y_eq).cwiseAbs().maxCoeff(), 1e-6 * (1.0 + k.y_eq.cwiseAbs().maxCoeff()))
        << "trial " << trial;
    if (k.y_box.size() > 0) {
      EXPECT_LT((s.yBox() - k.y_box).cwiseAbs().maxCoeff(), 1e-6) << "trial " << trial;
    }
  }
  std::printf("worst relative error of x: %.3g (trial %d)\n", worst, worst_trial);
}

TEST(QpSemidefinite, UnboundedProblemsAreNeverOptimal) {
  // f(x0 + t d) = f(x0) + t g'd with g'd < 0 along a feasible ray d of the null space of H: no optimum.
  std::mt19937 rng(152);
  for (int trial = 0; trial < 300; ++trial) {
    const int n = std::uniform_int_distribution<int>(1, 30)(rng);
    const int r = std::uniform_int_distribution<int>(0, n - 1)(rng);
    const DenseQp qp = centaur::test::unboundedQp(rng, n, r, false);
    QpSolver s = sizedFor(qp);
    EXPECT_NE(solveQp(s, qp), QpStatus::kOptimal)
        << "trial " << trial << " n " << n << " rank " << r << " |x| " << s.x().norm();
  }
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
  // H = M'M (rank n/2) + rel_reg * max(H_ii) * I: positive definite, condition number ~ 1 / rel_reg. Whatever the
  // status, an answer reported optimal is the optimum (Ipopt's, polished on its active set) and satisfies the KKT
  // conditions.
  std::mt19937 rng(154);
  QpSolver s(40, 42, 80);
  for (double rel_reg : {1e-4, 1e-6, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13}) {
    int optimal = 0, compared = 0;
    double worst_obj = 0.0, worst_kkt = 0.0;
    for (int trial = 0; trial < 150; ++trial) {
      const DenseQp qp = centaur::test::randomFeasible(rng, 40, rel_reg);
      if (solveQp(s, qp) != QpStatus::kOptimal) continue;
      ++optimal;
      const double kkt = kktResidual(qp, s);
      worst_kkt = std::max(worst_kkt, kkt);
      EXPECT_LT(kkt, 1e-9) << "rel_reg " << rel_reg << " trial " << trial;
      const auto oracle = centaur::test::solveWithIpopt(qp);
      VectorXd xp;
      if (oracle.x.size() != qp.n() || !centaur::test::polishOnActiveSet(qp, oracle.x, xp)) continue;
      ++compared;
      const double f = qp.objective(xp);
      const double rel = std::abs(s.objective() - f) / std::max(1.0, std::abs(f));
      worst_obj = std::max(worst_obj, rel);
      EXPECT_LT(rel, 1e-8) << "rel_reg " << rel_reg << " trial " << trial;
    }
    std::printf("relative regularisation %.0e: %d / 150 optimal, %d compared with Ipopt, worst objective difference "
                "%.2g, worst KKT residual %.2g\n", rel_reg, optimal, compared, worst_obj, worst_kkt);
  }
}
