// Offline planner: cold solve time and iterations of both jump primitives, and the cost of the NLP
// evaluations Ipopt asks for (constraint Jacobian, Lagrangian Hessian) and of one element's derivatives.
//   ./build/bench/bench_planner --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
// "Cold": the OCP is built from the configuration (structure analysis included) and solved from the default
// initial guess, nothing is reused between repetitions. Counters: iterations, ipopt_s (Ipopt's own wall time) or
// riccati_s (the structured backend's, *ColdRiccati), ms_per_iter (that time per iteration, build excluded), solved
// (1/0). The *ColdRiccati cases report real time (the backend runs on two threads); with
// --benchmark_repetitions they give the spread of single solves that `centaur bench planner` summarizes.
#include <benchmark/benchmark.h>

#include <chrono>
#include <random>

#include "common/retain_memory.hpp"
#include "model/template_params.hpp"
#include "ocp_solver/stage_kkt.hpp"
#include "planner/jump_problem.hpp"
#include "planner/ocp_nlp.hpp"
#include "planner/template_elements.hpp"

namespace {

using namespace centaur;
using namespace centaur::planner;
using namespace centaur::data;

void solveCold(benchmark::State& state, const std::string& primitive, const std::string& backend = "ipopt") {
  const JumpConfig cfg = loadJumpConfig(primitive, "", {"solver.backend=" + backend});
  int iterations = 0;
  double solve_s = 0.0;  // the solve's own wall time
  bool solved = true;
  for (auto _ : state) {
    const JumpProblem problem(cfg);
    const SolveResult r = problem.solve(false);
    iterations = r.info.iterations;
    solve_s = r.info.solve_time_s;
    solved = solved && r.info.solved();
    benchmark::DoNotOptimize(r.z.data());
  }
  state.counters["iterations"] = iterations;
  state.counters[backend + "_s"] = solve_s;
  state.counters["ms_per_iter"] = 1e3 * solve_s / std::max(1, iterations);
  state.counters["solved"] = solved ? 1 : 0;
}

void BM_SquatJumpCold(benchmark::State& state) { solveCold(state, "squat-jump"); }
void BM_HalfSquatJumpCold(benchmark::State& state) { solveCold(state, "half-squat-jump"); }
BENCHMARK(BM_SquatJumpCold)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HalfSquatJumpCold)->Unit(benchmark::kMillisecond);
void BM_SquatJumpColdRiccati(benchmark::State& state) { solveCold(state, "squat-jump", "riccati"); }
void BM_HalfSquatJumpColdRiccati(benchmark::State& state) { solveCold(state, "half-squat-jump", "riccati"); }
BENCHMARK(BM_SquatJumpColdRiccati)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_HalfSquatJumpColdRiccati)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_BuildSquatJump(benchmark::State& state) {
  const JumpConfig cfg = loadJumpConfig("squat-jump", "", {});
  for (auto _ : state) {
    const JumpProblem problem(cfg);
    benchmark::DoNotOptimize(&problem);
  }
}
BENCHMARK(BM_BuildSquatJump)->Unit(benchmark::kMillisecond);

// Assembled NLP derivatives of the squat jump at a perturbed initial guess.
struct NlpPoint {
  JumpProblem problem;
  Eigen::VectorXd z, lambda;
  NlpPoint() : problem(loadJumpConfig("squat-jump", "", {})) {
    const Ocp& ocp = problem.ocp();
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    z = ocp.guess();
    for (int i = 0; i < z.size(); ++i) z[i] += 0.05 * U(rng) * ocp.scale()[i];
    lambda.resize(ocp.numConstraints());
    for (int j = 0; j < lambda.size(); ++j) lambda[j] = U(rng);
  }
};

void BM_NlpHessian(benchmark::State& state) {
  static const NlpPoint p;
  const Ocp& ocp = p.problem.ocp();
  std::vector<double> h(ocp.hessianNonzeros());
  for (auto _ : state) {
    ocp.hessian(p.z.data(), 0.7, p.lambda.data(), h.data());
    benchmark::DoNotOptimize(h.data());
  }
}
BENCHMARK(BM_NlpHessian)->Unit(benchmark::kMicrosecond);

void BM_NlpJacobian(benchmark::State& state) {
  static const NlpPoint p;
  const Ocp& ocp = p.problem.ocp();
  std::vector<double> j(ocp.jacobianNonzeros());
  for (auto _ : state) {
    ocp.jacobian(p.z.data(), j.data());
    benchmark::DoNotOptimize(j.data());
  }
}
BENCHMARK(BM_NlpJacobian)->Unit(benchmark::kMicrosecond);

void BM_NlpConstraintsAndGradient(benchmark::State& state) {
  static const NlpPoint p;
  const Ocp& ocp = p.problem.ocp();
  std::vector<double> g(ocp.numConstraints()), grad(ocp.numVariables());
  for (auto _ : state) {
    ocp.constraints(p.z.data(), g.data());
    ocp.gradient(p.z.data(), grad.data());
    benchmark::DoNotOptimize(g.data());
    benchmark::DoNotOptimize(grad.data());
  }
}
BENCHMARK(BM_NlpConstraintsAndGradient)->Unit(benchmark::kMicrosecond);

// What the riccati backend evaluates per iteration: gradient, Jacobian and Hessian at once (one tape per term,
// linear constraint Jacobians and quadratic cost Hessians cached), on 1 or 2 threads (Arg). Compare with
// BM_NlpHessian + BM_NlpJacobian + the gradient (what Ipopt asks for). Real time is the figure that counts
// with 2 threads.
void BM_NlpDerivatives(benchmark::State& state) {
  static const NlpPoint p;
  const Ocp& ocp = p.problem.ocp();
  OcpNlp nlp(ocp, true, nullptr, static_cast<int>(state.range(0)));
  Eigen::VectorXd g;
  std::vector<double> j(ocp.jacobianNonzeros()), h(ocp.hessianNonzeros());
  for (auto _ : state) {
    nlp.derivatives(p.z, 0.7, p.lambda, g, j.data(), h.data());
    benchmark::DoNotOptimize(h.data());
  }
}
BENCHMARK(BM_NlpDerivatives)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond)->UseRealTime();

// Setting up the NLP of a solve (every cold solve and re-plan does it): the split of the terms between the two
// derivative lists and the worker thread's start. Arg 1: with freed memory kept in the process, as `centaur` does
// (common::retainFreedMemory; it stays in effect for the benchmarks after this one).
void BM_NlpSetup(benchmark::State& state) {
  static const NlpPoint p;
  if (state.range(0) == 1) common::retainFreedMemory();
  for (auto _ : state) {
    OcpNlp nlp(p.problem.ocp(), true, nullptr, 2);
    benchmark::DoNotOptimize(&nlp);
  }
}
BENCHMARK(BM_NlpSetup)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

// The stage-wise KKT solver on the squat jump's Newton system at the perturbed guess (barrier diagonal 1,
// inequality rows condensed with weight 1): structure analysis, factorization and solve (with refinement).
struct KktPoint {
  NlpPoint p;
  OcpNlp nlp{p.problem.ocp(), true, nullptr};
  std::vector<double> jac, hess;
  Eigen::VectorXd dx, dc, rx, rc;
  KktPoint() {
    const Ocp& ocp = p.problem.ocp();
    jac.resize(ocp.jacobianNonzeros());
    hess.resize(ocp.hessianNonzeros());
    ocp.jacobian(p.z.data(), jac.data());
    ocp.hessian(p.z.data(), 1.0, Eigen::VectorXd::Zero(ocp.numConstraints()).eval().data(), hess.data());
    dx = Eigen::VectorXd::Constant(ocp.numVariables(), 1.0);
    dc.resize(ocp.numConstraints());
    const auto eq = nlp.equalityRows();
    for (int r = 0; r < dc.size(); ++r) dc[r] = eq[r] ? 0.0 : 1.0;
    rx = Eigen::VectorXd::Ones(ocp.numVariables());
    rc = Eigen::VectorXd::Ones(ocp.numConstraints());
  }
  ocp_solver::StageKktSolver solver() const {
    return ocp_solver::StageKktSolver(nlp.pattern(), nlp.stageLayout(), nlp.fixedVariables(), nlp.equalityRows());
  }
};

// Arg: 1 = the stage blocks filled and the row part of each stage run on a second thread ahead of the cost parts
// (setPipelined), as the planner does.
void BM_StageKktFactor(benchmark::State& state) {
  static KktPoint k;
  auto s = k.solver();
  s.setPipelined(state.range(0) == 1);
  int sum_carried = 0, max_state = 0;
  for (int i = 0; i <= k.p.problem.ocp().numIntervals(); ++i) {
    sum_carried += s.carriedSize(i);
    max_state = std::max(max_state, s.stateSize(i) + s.carriedSize(i));
  }
  ocp_solver::KktStatus st = ocp_solver::KktStatus::kOk;
  for (auto _ : state) st = s.factor(k.hess.data(), k.jac.data(), k.dx, k.dc);
  state.counters["status"] = static_cast<int>(st);
  state.counters["carried_mean"] = static_cast<double>(sum_carried) / (k.p.problem.ocp().numIntervals() + 1);
  state.counters["state_max"] = max_state;
}
BENCHMARK(BM_StageKktFactor)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond)->UseRealTime();

// The structure analysis of a solve's KKT solver (every cold solve and re-plan builds one).
void BM_StageKktAnalyze(benchmark::State& state) {
  static KktPoint k;
  for (auto _ : state) {
    auto s = k.solver();
    benchmark::DoNotOptimize(&s);
  }
}
BENCHMARK(BM_StageKktAnalyze)->Unit(benchmark::kMicrosecond);

void BM_StageKktSolve(benchmark::State& state) {
  static KktPoint k;
  auto s = k.solver();
  state.counters["status"] = static_cast<int>(s.factor(k.hess.data(), k.jac.data(), k.dx, k.dc));
  Eigen::VectorXd x, y;
  for (auto _ : state) {
    s.solve(k.rx, k.rc, x, y);
    benchmark::DoNotOptimize(x.data());
  }
  state.counters["residual"] = s.lastResidual();
}
BENCHMARK(BM_StageKktSolve)->Unit(benchmark::kMicrosecond);

// One direction of the adaptive barrier as the interior point computes it: a factorization, then the affine and the
// centring solve. 0: one after the other; 1: solveTwo, both in one pass over the factors (both with the pipelined
// factorization, so that the solves find the factors where the planner's do).
void BM_StageKktFactorAndTwoSolves(benchmark::State& state) {
  static KktPoint k;
  auto s = k.solver();
  s.setPipelined(true);
  const Eigen::VectorXd rx2 = 0.5 * k.rx, rc2 = k.rc.reverse();
  Eigen::VectorXd x1, y1, x2, y2;
  for (auto _ : state) {
    s.factor(k.hess.data(), k.jac.data(), k.dx, k.dc);
    if (state.range(0) == 1) {
      s.solveTwo({k.rx, k.rc, x1, y1}, {rx2, rc2, x2, y2});
    } else {
      s.solve(k.rx, k.rc, x1, y1);
      s.solve(rx2, rc2, x2, y2);
    }
    benchmark::DoNotOptimize(x2.data());
  }
}
BENCHMARK(BM_StageKktFactorAndTwoSolves)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond)->UseRealTime();

// One foot-dynamics element (25 inputs, 9 outputs, 13 nonlinear): the largest element of the OCP.
struct FootPoint {
  FootDynamicsElement e{model::templatePreset("centauro"), 0, 1000.0};
  double x[25], w[9];
  FootPoint() {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    for (double& v : x) v = U(rng);
    for (double& v : w) v = U(rng);
  }
};

void BM_FootDynamicsJacobian(benchmark::State& state) {
  const FootPoint p;
  double out[9], jac[9 * 25];
  for (auto _ : state) {
    p.e.evalJacobian(p.x, out, jac);
    benchmark::DoNotOptimize(jac);
  }
}
BENCHMARK(BM_FootDynamicsJacobian);

void BM_FootDynamicsHessian(benchmark::State& state) {
  const FootPoint p;
  double hess[25 * 25];
  for (auto _ : state) {
    p.e.evalHessian(p.x, p.w, hess);
    benchmark::DoNotOptimize(hess);
  }
}
BENCHMARK(BM_FootDynamicsHessian);

// Both at once, as the planner's derivatives evaluate them: the element's derivatives written out by hand.
void BM_FootDynamicsJacobianHessian(benchmark::State& state) {
  const FootPoint p;
  double out[9], jac[9 * 25], hess[25 * 25];
  for (auto _ : state) {
    p.e.evalJacobianHessian(p.x, p.w, out, jac, hess);
    benchmark::DoNotOptimize(jac);
    benchmark::DoNotOptimize(hess);
  }
}
BENCHMARK(BM_FootDynamicsJacobianHessian);

// The same by the generic AD (one tape recording; the forward sweep carries all 25 directions), for comparison.
void BM_FootDynamicsJacobianHessianTape(benchmark::State& state) {
  const FootPoint p;
  double out[9], jac[9 * 25], hess[25 * 25];
  for (auto _ : state) {
    p.e.FootDynamicsElement::Ad::evalJacobianHessian(p.x, p.w, out, jac, hess);
    benchmark::DoNotOptimize(jac);
    benchmark::DoNotOptimize(hess);
  }
}
BENCHMARK(BM_FootDynamicsJacobianHessianTape);

// The same Hessian by nested forward AD (the previous method), for comparison.
void BM_FootDynamicsHessianNestedForward(benchmark::State& state) {
  const FootPoint p;
  double hess[25 * 25];
  for (auto _ : state) {
    p.e.evalHessianForward(p.x, p.w, hess);
    benchmark::DoNotOptimize(hess);
  }
}
BENCHMARK(BM_FootDynamicsHessianNestedForward);

}  // namespace

BENCHMARK_MAIN();
