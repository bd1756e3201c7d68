// ctest-labels: unit
// solve() of the QP solver (every path: fast, dual method, refinement, proximal iterations, unbounded, failures) and
// update()+solve() of the hierarchical QP never allocate. Every heap allocation
// of this test binary is counted twice over: a replaced global operator new (C++ allocations) and malloc &
// friends interposed on glibc's (Eigen allocates with malloc, not operator new). Neither count may move
// during the loops.
#include <gtest/gtest.h>

#include "support/allocation_counter.hpp"

#include <atomic>
#include <cstdlib>
#include <new>
#include <random>
#include <vector>

#include "qp/hqp_solver.hpp"
#include "random_qp.hpp"
#include "toy_arm.hpp"

namespace {
long allocations() { return centaur_test::heapAllocations(); }
}  // namespace


using namespace centaur;
using Eigen::MatrixXd;
using Eigen::VectorXd;

TEST(QpAllocations, CountersSeeNewAndEigenAllocations) {
  const long before_new = allocations();
  int* volatile p = new int(3);
  delete p;
  EXPECT_EQ(allocations() - before_new, 1) << "operator new is counted, once";
  const long before_eigen = allocations();
  Eigen::VectorXd v = Eigen::VectorXd::LinSpaced(100, 0.0, 1.0);
  EXPECT_GE(allocations() - before_eigen, 1) << "Eigen's malloc is counted";
  EXPECT_DOUBLE_EQ(v.sum(), 50.0);
}

TEST(QpAllocations, QpSolveNeverAllocates) {
  // The benchmark size: 45 variables, 30 equalities, 90 inequality rows, box bounds; cold and warm solves.
  const int n = 45, m_eq = 30, m_in = 90;
  std::mt19937 rng(3);
  std::normal_distribution<double> N(0.0, 1.0);
  MatrixXd M(n, n), A(m_eq, n), C(m_in, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) M(i, j) = N(rng);
  for (int i = 0; i < m_eq; ++i)
    for (int j = 0; j < n; ++j) A(i, j) = N(rng);
  for (int i = 0; i < m_in; ++i)
    for (int j = 0; j < n; ++j) C(i, j) = N(rng);
  const MatrixXd H = M.transpose() * M / n + 0.1 * MatrixXd::Identity(n, n);
  VectorXd g(n), x0(n);
  for (int j = 0; j < n; ++j) {
    g[j] = 5.0 * N(rng);
    x0[j] = N(rng);
  }
  const VectorXd b = A * x0;
  const VectorXd c_lo = (C * x0).array() - 0.1, c_up = (C * x0).array() + 0.1;
  const VectorXd x_lo = x0.array() - 0.5, x_up = x0.array() + 0.5;
  QpSolver s(n, m_eq, m_in);
  VectorXd g2 = g;
  const long before = allocations();
  int active = 0;
  for (int k = 0; k < 200; ++k) {
    if (k % 50 == 0) s.resetWarmStart();
    g2[k % n] += 0.01;
    const QpStatus st = s.solve(H, g2, A, b, C, c_lo, c_up, x_lo, x_up);
    if (st != QpStatus::kOptimal) break;
    active += s.numActive() - m_eq;
  }
  const long count = allocations() - before;
  EXPECT_EQ(count, 0);
  EXPECT_EQ(s.status(), QpStatus::kOptimal);
  EXPECT_GT(active, 0);  // inequalities were active: the active-set machinery ran
}

TEST(QpAllocations, HqpUpdateAndSolveNeverAllocate) {
  using centaur::test::PlanarArm;
  PlanarArm arm(6);
  arm.q.setConstant(0.2);
  auto tip = std::make_shared<centaur::test::TipPositionTask>("tip", arm);
  auto posture = std::make_shared<centaur::test::PostureTask>("posture", arm);
  auto extra = std::make_shared<LinearTask>("extra", MatrixXd::Ones(1, 6), VectorXd::Ones(1));
  auto pos = std::make_shared<JointPositionLimits>("q", 6, 0, VectorXd::Constant(6, -0.5), VectorXd::Constant(6, 1.0),
                                                   1e-3);
  auto vel = std::make_shared<JointVelocityLimits>("qd", 6, 0, VectorXd::Constant(6, 1.0));
  auto row = std::make_shared<LinearConstraint>("row", 6, 1);
  row->C().setOnes();
  row->cUpper()[0] = 2.0;
  tip->setLambda(10.0);
  tip->target = Eigen::Vector2d(0.3, 0.7);
  HqpSolver hqp(tip / (extra % Rows{0}) / (posture + 0.5 * extra) << pos << vel << row, 6);
  VectorXd qd(6);
  const long before = allocations();
  int ok = 0;
  for (int k = 0; k < 1000; ++k) {
    if (k % 250 == 0) tip->target = Eigen::Vector2d(0.3 - 0.001 * k, 0.7);
    if (k == 500) hqp.levelSolver(1).resetWarmStart();
    pos->setJointPositions(arm.q);
    hqp.update();
    const QpStatus st = hqp.solve(qd);
    if (st == QpStatus::kOptimal) ++ok;
    arm.q += 1e-3 * qd;
  }
  EXPECT_EQ(allocations() - before, 0);
  EXPECT_EQ(ok, 1000);
}

TEST(QpAllocations, LargestSizesNeverAllocate) {
  // The largest sizes planned for (100 variables, 100 equality rows of which some dependent, 200 rows) and a
  // 3-level cascade over 100 variables: Eigen's blocked kernels must stay on the stack too.
  const int n = 100, m_eq = 100, m_in = 200;
  std::mt19937 rng(9);
  std::normal_distribution<double> N(0.0, 1.0);
  auto randn = [&](int r, int c) {
    MatrixXd M(r, c);
    for (int i = 0; i < M.size(); ++i) M.data()[i] = N(rng);
    return M;
  };
  const MatrixXd M = randn(n, n);
  const MatrixXd H = M.transpose() * M / n + 0.1 * MatrixXd::Identity(n, n);
  MatrixXd A = randn(m_eq, n);
  A.bottomRows(20) = A.topRows(20);  // dependent rows (rank 80)
  const MatrixXd C = randn(m_in, n);
  const VectorXd x0 = randn(n, 1), g = 5.0 * randn(n, 1);
  const VectorXd b = A * x0;
  const VectorXd c_lo = (C * x0).array() - 0.2, c_up = (C * x0).array() + 0.2;
  const VectorXd x_lo = x0.array() - 0.3, x_up = x0.array() + 0.3;
  QpSolver s(n, m_eq, m_in);
  long before = allocations();
  ASSERT_EQ(s.solve(H, g, A, b, C, c_lo, c_up, x_lo, x_up), QpStatus::kOptimal);
  ASSERT_EQ(s.solve(H, g, A, b, C, c_lo, c_up, x_lo, x_up), QpStatus::kOptimal);  // warm
  EXPECT_EQ(allocations() - before, 0);
  EXPECT_GT(s.numActive(), 80);

  auto t0 = std::make_shared<LinearTask>("t0", randn(40, n), randn(40, 1));
  auto t1 = std::make_shared<LinearTask>("t1", randn(30, n), randn(30, 1));
  auto t2 = std::make_shared<LinearTask>("t2", MatrixXd::Identity(n, n), randn(n, 1));
  auto lim = std::make_shared<LinearConstraint>("lim", n, m_in);
  lim->C() = C;
  lim->cLower() = c_lo - C * x0;  // x = 0 feasible
  lim->cUpper() = c_up - C * x0;
  lim->lowerBounds().setConstant(-0.3);
  lim->upperBounds().setConstant(0.3);
  HqpSolver hqp(t0 / t1 / (t2 + t0 % Rows{0, 1}) << lim, n);
  VectorXd x(n);
  before = allocations();
  int ok = 0;
  for (int k = 0; k < 20; ++k) {
    t0->b()[0] += 0.01;
    hqp.update();
    if (hqp.solve(x) == QpStatus::kOptimal) ++ok;
  }
  EXPECT_EQ(allocations() - before, 0);
  EXPECT_EQ(ok, 20);
}

TEST(QpAllocations, SingularUnboundedAndRejectedSolvesNeverAllocate) {
  // The paths behind the KKT check: proximal-point iterations on a rank-deficient H (polished on their active set),
  // an unbounded problem (ray), a failed KKT check with refinement and fallback (kInaccurate), a proximal iteration
  // limit, and infeasibility confirmed after refining. Each status is the expected one: the path did run.
  std::mt19937 rng(11);
  struct Case {
    centaur::test::DenseQp qp;
    QpStatus expected;
    double kkt_tol;
    int max_prox;
  };
  std::vector<Case> cases;
  const centaur::test::KnownQp singular = centaur::test::knownAnswer(rng, 30, 12);
  cases.push_back({singular.qp, QpStatus::kOptimal, 1e-9, 100});
  cases.push_back({centaur::test::knownAnswer(rng, 100, 40).qp, QpStatus::kOptimal, 1e-9, 100});  // largest size
  cases.push_back({centaur::test::unboundedQp(rng, 30, 20, false), QpStatus::kUnbounded, 1e-9, 100});
  cases.push_back({centaur::test::unboundedQp(rng, 30, 20, false), QpStatus::kIterationLimit, 1e-9, 1});
  cases.push_back({centaur::test::knownAnswer(rng, 30, 30).qp, QpStatus::kInaccurate, 1e-30, 100});
  centaur::test::DenseQp infeasible = centaur::test::knownAnswer(rng, 30, 30).qp;
  infeasible.C.conservativeResize(infeasible.C.rows() + 2, 30);
  infeasible.c_lo.conservativeResize(infeasible.C.rows());
  infeasible.c_up.conservativeResize(infeasible.C.rows());
  infeasible.C.bottomRows(2).setOnes();
  infeasible.c_lo.tail(2) << 1.0, -centaur::test::kInf;
  infeasible.c_up.tail(2) << centaur::test::kInf, -1.0;
  cases.push_back({infeasible, QpStatus::kInfeasible, 1e-9, 100});
  int m_eq = 0, m_in = 0;
  for (const Case& c : cases) {
    m_eq = std::max(m_eq, static_cast<int>(c.qp.A_eq.rows()));
    m_in = std::max(m_in, static_cast<int>(c.qp.C.rows()));
  }
  QpSolver s(100, m_eq, m_in);
  int matched = 0, prox = 0;
  const long before = allocations();
  for (int round = 0; round < 3; ++round)
    for (const Case& c : cases) {
      s.settings().kkt_tol = c.kkt_tol;
      s.settings().max_proximal_iterations = c.max_prox;
      matched += centaur::test::solveQp(s, c.qp) == c.expected;
      prox += s.proximalIterations();
    }
  EXPECT_EQ(allocations() - before, 0);
  EXPECT_EQ(matched, 3 * static_cast<int>(cases.size()));
  EXPECT_GT(prox, 0);
}
