// Dense QP (Goldfarb-Idnani) and hierarchical QP solve times at the sizes of the 1 kHz whole-body stack.
//   ./build/bench/bench_qp --benchmark_repetitions=10 --benchmark_report_aggregates_only=true
// Cold: the warm start is forgotten before each solve (memory stays allocated). Warm: successive solves of
// slowly drifting problems, as in consecutive control ticks.
#include <benchmark/benchmark.h>

#include <random>

#include "qp/hqp_solver.hpp"
#include "qp/qp_solver.hpp"

namespace {

using centaur::QpSolver;
using centaur::QpStatus;
using Eigen::MatrixXd;
using Eigen::VectorXd;

struct Problem {
  MatrixXd H, A, C;
  VectorXd g, b, c_lo, c_up, x_lo, x_up;
};

// n variables, m_eq equalities, m_in two-sided rows, box bounds; feasible at a random x0, with g pulling away
// from it so that a realistic number of inequalities (~10-20) is active at the optimum.
Problem makeProblem(int n, int m_eq, int m_in, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> N(0.0, 1.0);
  Problem p;
  MatrixXd M(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) M(i, j) = N(rng);
  p.H = M.transpose() * M / n + 0.05 * MatrixXd::Identity(n, n);
  VectorXd x0(n);
  p.g.resize(n);
  for (int j = 0; j < n; ++j) {
    x0[j] = N(rng);
    p.g[j] = 3.0 * N(rng);
  }
  p.A.resize(m_eq, n);
  for (int i = 0; i < m_eq; ++i)
    for (int j = 0; j < n; ++j) p.A(i, j) = N(rng);
  p.b = p.A * x0;
  p.C.resize(m_in, n);
  for (int i = 0; i < m_in; ++i)
    for (int j = 0; j < n; ++j) p.C(i, j) = N(rng);
  const VectorXd cx = p.C * x0;
  p.c_lo = cx.array() - 0.5;
  p.c_up = cx.array() + 0.5;
  p.x_lo = x0.array() - 1.0;
  p.x_up = x0.array() + 1.0;
  return p;
}

void BM_QpCold(benchmark::State& state) {
  const int n = 45, m_eq = 30, m_in = 90;
  const Problem p = makeProblem(n, m_eq, m_in, 1);
  QpSolver s(n, m_eq, m_in);
  int active = 0;
  for (auto _ : state) {
    s.resetWarmStart();
    const QpStatus st = s.solve(p.H, p.g, p.A, p.b, p.C, p.c_lo, p.c_up, p.x_lo, p.x_up);
    if (st != QpStatus::kOptimal) state.SkipWithError("QP not optimal");
    active = s.numActive() - m_eq;
  }
  state.counters["active_ineq"] = active;
  state.counters["iterations"] = s.iterations();
}
BENCHMARK(BM_QpCold)->Unit(benchmark::kMicrosecond);

void BM_QpWarm(benchmark::State& state) {
  const int n = 45, m_eq = 30, m_in = 90;
  Problem p = makeProblem(n, m_eq, m_in, 1);
  QpSolver s(n, m_eq, m_in);
  const VectorXd g0 = p.g;
  long k = 0;
  double iterations = 0.0;
  for (auto _ : state) {
    // A tick-to-tick drift of the linear term.
    p.g = g0 + 0.01 * std::sin(0.01 * static_cast<double>(k)) * VectorXd::Ones(n);
    const QpStatus st = s.solve(p.H, p.g, p.A, p.b, p.C, p.c_lo, p.c_up, p.x_lo, p.x_up);
    if (st != QpStatus::kOptimal) state.SkipWithError("QP not optimal");
    iterations += s.iterations();
    ++k;
  }
  state.counters["active_ineq"] = s.numActive() - m_eq;
  state.counters["iterations_mean"] = iterations / std::max(1L, k);
}
BENCHMARK(BM_QpWarm)->Unit(benchmark::kMicrosecond);

// The same constraints with a singular H (rank 30 of 45, no regularisation): the proximal-point iterations
// (docs/qp.md), which the controller never needs (its Hessians are regularised): what a singular H costs.
void BM_QpSingularCold(benchmark::State& state) {
  const int n = 45, m_eq = 30, m_in = 90, rank = 30;
  Problem p = makeProblem(n, m_eq, m_in, 1);
  std::mt19937 rng(5);
  std::normal_distribution<double> N(0.0, 1.0);
  MatrixXd M(rank, n);
  for (int i = 0; i < M.size(); ++i) M.data()[i] = N(rng);
  p.H = M.transpose() * M / n;
  QpSolver s(n, m_eq, m_in);
  for (auto _ : state) {
    s.resetWarmStart();
    const QpStatus st = s.solve(p.H, p.g, p.A, p.b, p.C, p.c_lo, p.c_up, p.x_lo, p.x_up);
    if (st != QpStatus::kOptimal) state.SkipWithError("QP not optimal");
  }
  state.counters["proximal_iterations"] = s.proximalIterations();
  state.counters["iterations"] = s.iterations();
}
BENCHMARK(BM_QpSingularCold)->Unit(benchmark::kMicrosecond);

// 3-level cascade: 45 variables; level 0 has 30 rows (its residuals are 30 equalities below), level 1 six rows,
// level 2 a 45-row posture plus 6 rows; 90 inequality rows and box bounds at every level.
struct Cascade {
  std::shared_ptr<centaur::LinearTask> t0, t1, t2a, t2b;
  std::shared_ptr<centaur::LinearConstraint> limits;
  centaur::HqpSolver hqp;
  VectorXd b0;

  Cascade() {
    using namespace centaur;
    const int n = 45;
    const Problem p = makeProblem(n, 30, 90, 2);
    std::mt19937 rng(3);
    std::normal_distribution<double> N(0.0, 1.0);
    auto rnd = [&](int rows) {
      MatrixXd A(rows, n);
      for (int i = 0; i < rows; ++i)
        for (int j = 0; j < n; ++j) A(i, j) = N(rng);
      return A;
    };
    auto rndv = [&](int rows) {
      VectorXd v(rows);
      for (int i = 0; i < rows; ++i) v[i] = N(rng);
      return v;
    };
    t0 = std::make_shared<LinearTask>("feet", p.A, p.b + 0.1 * rndv(30));
    t1 = std::make_shared<LinearTask>("pelvis", rnd(6), rndv(6));
    t2a = std::make_shared<LinearTask>("ang_mom", rnd(6), rndv(6));
    t2b = std::make_shared<LinearTask>("posture", MatrixXd::Identity(n, n), 3.0 * rndv(n));
    limits = std::make_shared<LinearConstraint>("limits", n, 90);
    limits->C() = p.C;
    limits->cLower() = p.c_lo;
    limits->cUpper() = p.c_up;
    limits->lowerBounds() = p.x_lo;
    limits->upperBounds() = p.x_up;
    hqp.configure((t0 / t1) / (t2a + 0.1 * t2b) << limits, n);
    b0 = t0->b();
  }
};

void BM_HqpCascadeCold(benchmark::State& state) {
  Cascade c;
  VectorXd x(45);
  for (auto _ : state) {
    for (int k = 0; k < c.hqp.numLevels(); ++k) c.hqp.levelSolver(k).resetWarmStart();
    if (c.hqp.solve(x) != QpStatus::kOptimal) state.SkipWithError("HQP not optimal");
  }
}
BENCHMARK(BM_HqpCascadeCold)->Unit(benchmark::kMicrosecond);

void BM_HqpCascadeWarm(benchmark::State& state) {
  Cascade c;
  VectorXd x(45);
  long k = 0;
  for (auto _ : state) {
    c.t0->b() = c.b0 + 0.01 * std::sin(0.01 * static_cast<double>(k++)) * VectorXd::Ones(30);
    if (c.hqp.solve(x) != QpStatus::kOptimal) state.SkipWithError("HQP not optimal");
  }
}
BENCHMARK(BM_HqpCascadeWarm)->Unit(benchmark::kMicrosecond);

// The shape of the CENTAURO stack: x = [base twist (6); qd (39)]; feet (4 x 6 rows) / pelvis angular
// velocity (3) / (angular momentum (3) + posture (39)), joint position and velocity limits as box bounds only.
// Random Jacobian-like rows stand in for the model; warm, with a drifting feet target.
void BM_HqpCentauroShapeWarm(benchmark::State& state) {
  using namespace centaur;
  const int n = 45, nj = 39;
  std::mt19937 rng(4);
  std::normal_distribution<double> N(0.0, 1.0);
  auto rnd = [&](int rows, int cols) {
    MatrixXd A(rows, cols);
    for (int i = 0; i < A.size(); ++i) A.data()[i] = N(rng);
    return A;
  };
  auto feet = std::make_shared<LinearTask>("feet", rnd(24, n), rnd(24, 1));
  auto pelvis = std::make_shared<LinearTask>("pelvis", rnd(3, n), rnd(3, 1));
  auto ang_mom = std::make_shared<LinearTask>("ang_mom", rnd(3, n), rnd(3, 1));
  MatrixXd P = MatrixXd::Zero(nj, n);
  P.rightCols(nj).setIdentity();
  auto posture = std::make_shared<LinearTask>("posture", P, 3.0 * rnd(nj, 1));
  const VectorXd q_min = VectorXd::Constant(nj, -1.0), q_max = VectorXd::Constant(nj, 1.0);
  auto pos = std::make_shared<JointPositionLimits>("q", n, 6, q_min, q_max, 1e-3, 0.5);
  auto vel = std::make_shared<JointVelocityLimits>("qd", n, 6, VectorXd::Constant(nj, 2.0));
  VectorXd q = 0.9 * rnd(nj, 1).cwiseMax(-1.0).cwiseMin(1.0);
  pos->setJointPositions(q);
  HqpSolver hqp((feet / pelvis) / (ang_mom + 0.01 * posture) << pos << vel, n);
  const VectorXd b0 = feet->b();
  VectorXd x(n);
  long k = 0;
  for (auto _ : state) {
    feet->b() = b0 + 0.01 * std::sin(0.01 * static_cast<double>(k++)) * VectorXd::Ones(24);
    hqp.update();
    if (hqp.solve(x) != QpStatus::kOptimal) state.SkipWithError("HQP not optimal");
  }
  state.counters["active_level0"] = hqp.levelSolver(0).numActive();
}
BENCHMARK(BM_HqpCentauroShapeWarm)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
