#include "cli/bench_planner.hpp"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <map>
#include <vector>

#include "common/stats.hpp"
#include "planner/jump_problem.hpp"

namespace centaur::cli {
namespace {

const std::vector<std::string> kBackends = {"ipopt", "riccati"};

// The solves of one backend (one entry per cold run).
struct BackendRuns {
  std::vector<double> wall, cpu, derivatives, functions, factor, kkt_solve;
  int iterations = 0, factorizations = -1;
  double cost = 0.0;
  std::string status;
};

nlohmann::json backendJson(const BackendRuns& r) {
  nlohmann::json j;
  j["status"] = r.status;
  j["iterations"] = r.iterations;
  j["cost"] = r.cost;
  j["solve_wall_s_median"] = median(r.wall);
  j["solve_wall_s"] = r.wall;  // every run, in the order they ran (the spread the median hides)
  j["solve_cpu_s_median"] = median(r.cpu);
  j["ms_per_iteration"] = r.iterations > 0 ? 1e3 * median(r.wall) / r.iterations : 0.0;
  j["derivative_wall_s_median"] = median(r.derivatives);
  j["function_wall_s_median"] = median(r.functions);
  if (r.factorizations >= 0) {
    j["factorizations_per_iteration"] = r.iterations > 0 ? static_cast<double>(r.factorizations) / r.iterations : 0.0;
    j["factor_wall_s_median"] = median(r.factor);
    j["kkt_solve_wall_s_median"] = median(r.kkt_solve);
  }
  return j;
}

std::vector<std::string> neighbours(const std::string& primitive) {
  if (primitive == "half-squat-jump") return {"target.wall_distance=0.12", "target.wall_distance=0.18"};
  return {"target.height=0.82", "target.height=0.92"};
}

planner::JumpConfig configWith(const std::string& primitive, const std::string& backend,
                               const std::vector<std::string>& sets, const std::vector<std::string>& overrides) {
  std::vector<std::string> all = sets;
  all.insert(all.end(), overrides.begin(), overrides.end());
  planner::JumpConfig cfg = planner::loadJumpConfig(primitive, "", all);
  cfg.solver.backend = backend;
  return cfg;
}

}  // namespace

void checkPlannerOverrides(const std::vector<std::string>& sets) {
  for (const std::string p : {"squat-jump", "half-squat-jump"}) planner::loadJumpConfig(p, "", sets);
}

// Cold solves with both backends, interleaved run by run so that a change of the machine's speed affects both
// alike. The top-level fields are those of the configured default backend.
nlohmann::json benchPrimitive(const std::string& primitive, int repeat, const std::vector<std::string>& sets) {
  std::map<std::string, BackendRuns> runs;
  std::vector<double> setup;
  std::string default_backend;
  for (int r = 0; r < repeat; ++r) {
    for (const std::string& b : kBackends) {
      const auto t0 = std::chrono::steady_clock::now();
      planner::JumpConfig cfg = planner::loadJumpConfig(primitive, "", sets);
      default_backend = cfg.solver.backend;
      cfg.solver.backend = b;
      const planner::JumpProblem problem(cfg);
      const auto t1 = std::chrono::steady_clock::now();
      const std::clock_t c1 = std::clock();
      const auto res = problem.solve(false);
      const auto t2 = std::chrono::steady_clock::now();
      const std::clock_t c2 = std::clock();
      if (b == default_backend) setup.push_back(std::chrono::duration<double>(t1 - t0).count());
      BackendRuns& br = runs[b];
      br.wall.push_back(std::chrono::duration<double>(t2 - t1).count());
      br.cpu.push_back(static_cast<double>(c2 - c1) / CLOCKS_PER_SEC);
      br.derivatives.push_back(res.stats.derivative_time_s);
      br.functions.push_back(res.stats.function_time_s);
      br.factor.push_back(res.stats.factor_time_s);
      br.kkt_solve.push_back(res.stats.linear_solve_time_s);
      br.iterations = res.info.iterations;
      br.factorizations = res.stats.factorizations;
      br.cost = res.info.cost;
      br.status = res.info.status;
    }
  }
  nlohmann::json j = backendJson(runs[default_backend]);
  j["ms_per_iteration"] = runs[default_backend].iterations > 0
                              ? 1e3 * median(runs[default_backend].cpu) / runs[default_backend].iterations
                              : 0.0;  // CPU per iteration, as before the backends
  j["setup_wall_s_median"] = median(setup);
  j["repeat"] = repeat;
  j["set"] = sets;
  j["backend"] = default_backend;
  for (const std::string& b : kBackends) j["backends"][b] = backendJson(runs[b]);
  const double wi = median(runs["ipopt"].wall), wr = median(runs["riccati"].wall);
  j["riccati_speedup_wall"] = wr > 0.0 ? wi / wr : 0.0;
  return j;
}

// Warm re-plans of the neighbours, each backend from its own default plan (solved cold once), interleaved.
nlohmann::json benchWarmReplan(const std::string& primitive, int repeat, const std::vector<std::string>& sets) {
  const std::vector<std::string> near = neighbours(primitive);
  // The default plan of each backend, the source of its warm starts.
  std::map<std::string, data::Primitive> source;
  for (const std::string& b : kBackends) {
    const planner::JumpProblem p(configWith(primitive, b, sets, {}));
    source.emplace(b, p.toPrimitive(p.solve(false)));
  }
  struct Runs {
    std::vector<double> wall;
    int iterations = 0;
    double cost = 0.0;
    std::string status;
    std::string start;  // primal-dual | knots
  };
  std::map<std::string, std::map<std::string, Runs>> runs;  // backend -> neighbour -> runs
  for (int r = 0; r < repeat; ++r) {
    for (const std::string& n : near) {
      for (const std::string& b : kBackends) {
        const planner::JumpProblem p(configWith(primitive, b, sets, {n}));
        const planner::WarmStartPoint warm = p.warmStart(source.at(b), "the default " + primitive + " plan");
        const auto t0 = std::chrono::steady_clock::now();
        const planner::SolveResult res = p.solve(false, warm);
        const auto t1 = std::chrono::steady_clock::now();
        Runs& e = runs[b][n];
        e.wall.push_back(std::chrono::duration<double>(t1 - t0).count());
        e.iterations = res.info.iterations;
        e.cost = res.info.cost;
        e.status = res.info.status;
        e.start = warm.hasMultipliers() ? "primal-dual" : "knots";
      }
    }
  }
  nlohmann::json j;
  j["from"] = "defaults";
  j["neighbours"] = near;
  j["repeat"] = repeat;
  for (const std::string& b : kBackends) {
    double worst = 0.0;
    for (const std::string& n : near) {
      const Runs& e = runs[b][n];
      nlohmann::json& jn = j["backends"][b][n];
      jn["status"] = e.status;
      jn["start"] = e.start;
      jn["iterations"] = e.iterations;
      jn["cost"] = e.cost;
      jn["solve_wall_s_median"] = median(e.wall);
      jn["solve_wall_s"] = e.wall;
      worst = std::max(worst, median(e.wall));
    }
    j["backends"][b]["solve_wall_s_median_max"] = worst;  // the slowest neighbour
  }
  return j;
}

}  // namespace centaur::cli
