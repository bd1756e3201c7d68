// `centaur bench planner`: both backends solve both jumps cold (5 times by default) and re-plan their neighbours
// warm, and the last stdout line is a JSON object whose summaries agree with the solves it lists. Timings are only
// checked for consistency (every run listed, the medians and the speed-up computed from them), never against a
// budget.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "common/stats.hpp"
#include "support/cli_run.hpp"

namespace {

using centaur_test::CliRun;
using centaur_test::run;

// `runs` lists `repeat` positive wall times whose median is the entry's solve_wall_s_median.
void expectRunsAndMedian(const nlohmann::json& entry, int repeat, const std::string& what) {
  const std::vector<double> runs = entry.at("solve_wall_s").get<std::vector<double>>();
  ASSERT_EQ(static_cast<int>(runs.size()), repeat) << what;
  for (double t : runs) EXPECT_GT(t, 0.0) << what;
  EXPECT_DOUBLE_EQ(entry.at("solve_wall_s_median").get<double>(), centaur::median(runs)) << what;
}

}  // namespace

TEST(BenchPlannerCli, ListsEverySolveAndBothBackendsReachTheSameOptima) {
  const int repeat = 5;  // the planner's default: medians of 5 solves
  const CliRun r = run("bench planner --json", false, 600);
  ASSERT_EQ(r.code, 0) << r.out;
  const nlohmann::json j = nlohmann::json::parse(r.last_line).at("planner");
  for (const std::string primitive : {"squat-jump", "half-squat-jump"}) {
    const nlohmann::json& p = j.at(primitive);
    EXPECT_EQ(p.at("repeat"), repeat);
    EXPECT_TRUE(p.at("set").empty());
    const nlohmann::json& ipopt = p.at("backends").at("ipopt");
    const nlohmann::json& riccati = p.at("backends").at("riccati");
    for (const auto& [name, b] : p.at("backends").items()) {
      EXPECT_EQ(b.at("status"), "solved") << primitive << " " << name;
      EXPECT_GT(b.at("iterations").get<int>(), 0) << primitive << " " << name;
      expectRunsAndMedian(b, repeat, primitive + " " + name);
    }
    // The default jumps are points where the two methods reach the same local optimum (docs/planner.md).
    const double ci = ipopt.at("cost"), cr = riccati.at("cost");
    EXPECT_LT(std::abs(ci - cr), 1e-5 * std::abs(ci)) << primitive;
    EXPECT_DOUBLE_EQ(p.at("riccati_speedup_wall").get<double>(),
                     ipopt.at("solve_wall_s_median").get<double>() / riccati.at("solve_wall_s_median").get<double>());
    EXPECT_GT(riccati.at("factorizations_per_iteration").get<double>(), 1.0);  // inertia corrections included

    const nlohmann::json& warm = p.at("warm_replan");
    ASSERT_EQ(warm.at("neighbours").size(), 2u) << primitive;
    for (const auto& [name, b] : warm.at("backends").items()) {
      double slowest = 0.0;
      for (const std::string n : warm.at("neighbours")) {
        const nlohmann::json& e = b.at(n);
        EXPECT_EQ(e.at("status"), "solved") << primitive << " " << name << " " << n;
        EXPECT_EQ(e.at("start"), "primal-dual") << primitive << " " << name << " " << n;
        expectRunsAndMedian(e, repeat, primitive + " " + name + " " + n);
        slowest = std::max(slowest, e.at("solve_wall_s_median").get<double>());
      }
      EXPECT_DOUBLE_EQ(b.at("solve_wall_s_median_max").get<double>(), slowest) << primitive << " " << name;
    }
  }
}
