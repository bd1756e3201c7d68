// `centaur bench tick`: the whole-body tick benchmark runs end to end, prints one JSON object as the last
// stdout line with the documented keys, the controller stays nominal, and a bad stack file is exit code 2.
// (Timings are only checked for consistency, never against a budget: performance is not asserted in tests.)
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cstdio>
#include <string>
#include <sys/wait.h>
#include "robot/robot_registry.hpp"
#include "support/cli_run.hpp"

namespace {

using centaur_test::CliRun;
using centaur_test::run;

}  // namespace

TEST(BenchTickCli, PrintsTickAndQpTimesAsTheLastJsonLine) {
  const CliRun r = run("bench tick --ticks 300 --json");
  ASSERT_EQ(r.code, 0) << r.out;
  const nlohmann::json j = nlohmann::json::parse(r.last_line);
  EXPECT_EQ(j.at("target"), "tick");
  EXPECT_EQ(j.at("ticks"), 300);
  EXPECT_EQ(j.at("status"), "ok");
  EXPECT_EQ(j.at("safe_ticks"), 0);
  const double med = j.at("tick_us_median"), p99 = j.at("tick_us_p99"), qp = j.at("qp_us_median");
  EXPECT_GT(qp, 0.0);
  EXPECT_GT(med, qp);  // the HQP is a part of the tick
  EXPECT_GE(p99, med);
  EXPECT_GE(j.at("tick_us_max").get<double>(), p99);
  EXPECT_LT(j.at("pelvis_drift_m").get<double>(), 0.01);
}

TEST(BenchTickCli, MissingStackFileIsBadInput) {
  const CliRun r = run("bench tick --ticks 10 --stack /nonexistent/stack.yaml");
  EXPECT_EQ(r.code, 2);
}

TEST(BenchTickCli, EveryShippedRobotTicksStandingUnderTheWholeBodyController) {
  for (const std::string& robot : centaur::robot::robotNames()) {
    const CliRun r = run("bench tick --ticks 300 --robot " + robot + " --json");
    ASSERT_EQ(r.code, 0) << r.out;
    const nlohmann::json j = nlohmann::json::parse(r.last_line);
    EXPECT_EQ(j.at("robot"), robot);
    EXPECT_EQ(j.at("status"), "ok") << robot;
    EXPECT_EQ(j.at("safe_ticks"), 0) << robot;
    EXPECT_LT(j.at("pelvis_drift_m").get<double>(), 0.01) << robot;  // the stack holds the robot where it stands
  }
  EXPECT_EQ(run("bench tick --ticks 10 --robot no-such-robot").code, 2);
}
