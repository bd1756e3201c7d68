// The structured KKT factorization (ocp_solver/riccati.hpp) on systems of the planner's sizes.
//   ./build/bench/bench_ocp_solver --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
// Args: state dimension (37 = the jump's state; 55 = plus the 18 carried accelerations of the rate cost),
// controls 31, 30 stages, 6 mixed rows per stage and 12 pure-state rows (pinned feet) on the stance stages.
#include <benchmark/benchmark.h>

#include <random>

#include "ocp_solver/riccati.hpp"

namespace {

using namespace centaur::ocp_solver;

std::vector<StageQp> plannerSized(int nx) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  auto mat = [&](int r, int c) {
    Eigen::MatrixXd a(r, c);
    for (int j = 0; j < c; ++j)
      for (int i = 0; i < r; ++i) a(i, j) = U(rng);
    return a;
  };
  const int N = 30;
  std::vector<StageQp> qp(N + 1);
  for (int k = 0; k <= N; ++k) {
    const int nu = k < N ? 31 : 0;
    const int mixed = k < N ? 6 : 0, state = (k > 0 && (k <= 11 || k >= 20)) ? 12 : 0, fixed = k == 0 ? nx : 0;
    StageQp& s = qp[k];
    s.resize(nx, nu, mixed + state + fixed, k < N ? nx : 0);
    const Eigen::MatrixXd R = mat(nx + nu, nx + nu);
    s.H = R * R.transpose() / (nx + nu) + 0.01 * Eigen::MatrixXd::Identity(nx + nu, nx + nu);
    s.h = mat(nx + nu, 1);
    for (int j = 0; j < mixed; ++j) s.C.row(j) = mat(1, nx + nu);
    for (int j = 0; j < state; ++j) s.C.row(mixed + j).head(nx) = mat(1, nx);
    for (int j = 0; j < fixed; ++j) s.C(mixed + state + j, j) = 1.0;
    s.c = mat(static_cast<int>(s.C.rows()), 1);
    if (k < N) {  // the jump's sparsity: q += nu dt (+ a 4 x 7 quaternion block), nu += nu_dot dt, dt column dense
      s.A = Eigen::MatrixXd::Identity(nx, nx);
      for (int i = 0; i < 18; ++i) s.A(i < 3 ? i : i + 1, 19 + i) = 0.08;
      s.A.block(3, 3, 4, 4) += 0.01 * mat(4, 4);
      s.A.block(3, 22, 4, 3) = 0.05 * mat(4, 3);
      for (int i = 0; i < 18; ++i) {
        s.B(i < 3 ? i : i + 1, i) = 0.0032;
        s.B(19 + i, i) = 0.08;
        if (nx > 37) s.B(37 + i, i) = 1.0;  // carried controls
      }
      s.B.block(0, 30, 37, 1) = mat(37, 1);
      s.b = mat(nx, 1);
    }
  }
  return qp;
}

// Args: the state size; 1 = the row parts on a second thread ahead of the cost parts (RiccatiSolver::setParallel).
void BM_RiccatiFactor(benchmark::State& state) {
  const auto qp = plannerSized(static_cast<int>(state.range(0)));
  RiccatiSolver solver;
  solver.setParallel(state.range(1) == 1);
  for (auto _ : state) benchmark::DoNotOptimize(solver.factor(qp));
}
BENCHMARK(BM_RiccatiFactor)->Args({37, 0})->Args({55, 0})->Args({55, 1})->Unit(benchmark::kMicrosecond)->UseRealTime();

void BM_RiccatiSolve(benchmark::State& state) {
  const auto qp = plannerSized(static_cast<int>(state.range(0)));
  RiccatiSolver solver;
  solver.factor(qp);
  std::vector<StageSolution> sol;
  for (auto _ : state) {
    solver.solve(qp, sol);
    benchmark::DoNotOptimize(sol.data());
  }
}
BENCHMARK(BM_RiccatiSolve)->Arg(37)->Arg(55)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
