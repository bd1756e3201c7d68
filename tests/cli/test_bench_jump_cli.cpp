// ctest-labels: integration cli
// `centaur bench jump`: the jumps' closed-loop real-time factor benchmark runs the requested (jump, mode) pairs,
// prints one JSON object as the last stdout line with an outcome and median/min/max real-time factor per pair, and
// refuses a missing primitive file or mode ocp without a flywheel file with exit code 2.
// (Timings are only checked for consistency, never against a budget: performance is not asserted in tests.)
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <string>

#include "support/cli_run.hpp"
#include "support/temp_dir.hpp"

namespace {

using centaur_test::CliRun;
using centaur_test::run;

}  // namespace

TEST(BenchJumpCli, ReportsTheRealTimeFactorOfEveryRequestedPair) {
  centaur_test::TempDir dir;
  const std::string prims = dir.file("prims.h5");
  ASSERT_EQ(run("plan squat-jump --quiet --out " + prims).code, 0);
  const CliRun r = run("bench jump --primitives " + prims + " --jumps squat-jump --modes none raibert --repeat 2 --json");
  ASSERT_EQ(r.code, 0) << r.out;
  const nlohmann::json j = nlohmann::json::parse(r.last_line);
  EXPECT_EQ(j.at("target"), "jump");
  EXPECT_EQ(j.at("repeat"), 2);
  ASSERT_EQ(j.at("runs").size(), 1u);
  ASSERT_EQ(j.at("runs").at("squat-jump").size(), 2u);
  for (const char* mode : {"none", "raibert"}) {
    const auto& e = j.at("runs").at("squat-jump").at(mode);
    EXPECT_EQ(e.at("outcome"), "success") << mode;
    const double lo = e.at("real_time_factor_min"), med = e.at("real_time_factor_median"),
                 hi = e.at("real_time_factor_max");
    EXPECT_GT(lo, 0.0) << mode;
    EXPECT_LE(lo, med) << mode;
    EXPECT_LE(med, hi) << mode;
  }
}

TEST(BenchJumpCli, MissingPrimitivesOrFlywheelIsBadInput) {
  EXPECT_EQ(run("bench jump").code, 2);
  EXPECT_EQ(run("bench jump --primitives /nonexistent/prims.h5").code, 2);
  centaur_test::TempDir dir;
  const std::string prims = dir.file("prims.h5");
  std::ofstream(prims) << "";  // exists (the flywheel is checked first, before the file is read)
  const CliRun r = run("bench jump --primitives " + prims + " --jumps squat-jump --modes ocp", true);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.out.find("--flywheel"), std::string::npos) << r.out;
}
