// centaur bench planner [--repeat N] [--json]
// Cold solves of both jump primitives with the embedded defaults; reports the median wall and CPU solve time,
// iterations and time per iteration. With --json the last stdout line is one JSON object.
// (Timings are measured, never asserted in tests; record them in docs/benchmarks.md.)
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>

#include "cli/command.hpp"
#include "common/error.hpp"
#include "planner/jump_problem.hpp"

namespace centaur::cli {
namespace {

struct BenchArgs {
  std::string target;
  int repeat = 3;
  bool json = false;
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

nlohmann::json benchPrimitive(const std::string& primitive, int repeat) {
  std::vector<double> wall, cpu, setup;
  int iterations = 0;
  std::string status;
  for (int r = 0; r < repeat; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    const std::clock_t c0 = std::clock();
    const planner::JumpConfig cfg = planner::loadJumpConfig(primitive, "", {});
    const planner::JumpProblem problem(cfg);
    const auto t1 = std::chrono::steady_clock::now();
    const std::clock_t c1 = std::clock();
    const auto res = problem.solve(false);
    const auto t2 = std::chrono::steady_clock::now();
    const std::clock_t c2 = std::clock();
    setup.push_back(std::chrono::duration<double>(t1 - t0).count());
    wall.push_back(std::chrono::duration<double>(t2 - t1).count());
    cpu.push_back(static_cast<double>(c2 - c1) / CLOCKS_PER_SEC);
    (void)c0;
    iterations = res.info.iterations;
    status = res.info.status;
  }
  nlohmann::json j;
  j["status"] = status;
  j["iterations"] = iterations;
  j["solve_wall_s_median"] = median(wall);
  j["solve_cpu_s_median"] = median(cpu);
  j["setup_wall_s_median"] = median(setup);
  j["ms_per_iteration"] = iterations > 0 ? 1e3 * median(cpu) / iterations : 0.0;
  j["repeat"] = repeat;
  return j;
}

int runBench(const BenchArgs& a) {
  nlohmann::json out;
  if (a.target == "planner") {
    for (const std::string p : {"squat-jump", "half-squat-jump"}) {
      std::fprintf(stderr, "bench planner %s: %d cold solves ...\n", p.c_str(), a.repeat);
      out["planner"][p] = benchPrimitive(p, a.repeat);
      const auto& j = out["planner"][p];
      std::fprintf(stderr, "  %-16s %s, %d iterations, median solve %.3f s wall / %.3f s CPU, %.1f ms per iteration\n",
                   p.c_str(), j["status"].get<std::string>().c_str(), j["iterations"].get<int>(),
                   j["solve_wall_s_median"].get<double>(), j["solve_cpu_s_median"].get<double>(),
                   j["ms_per_iteration"].get<double>());
    }
  }
  if (a.json) printJsonLine(out.dump());
  return kExitOk;
}

const Registrar kBench{{"bench", "Measure performance (planner: cold solves of both jumps)", [](CLI::App& sub) {
                          auto a = std::make_shared<BenchArgs>();
                          sub.add_option("target", a->target, "what to measure: planner")
                              ->required()
                              ->check(CLI::IsMember({"planner"}));
                          sub.add_option("--repeat", a->repeat, "cold runs per case (median reported)")
                              ->check(CLI::Range(1, 100));
                          sub.add_flag("--json", a->json, "print a JSON object as the last line of stdout");
                          return [a]() { return runBench(*a); };
                        }}};

}  // namespace
}  // namespace centaur::cli
