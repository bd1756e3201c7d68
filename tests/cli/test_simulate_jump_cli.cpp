// ctest-labels: integration cli
// `centaur simulate squat-jump|half-squat-jump`: bad input (missing primitive file, a file without the jump's
// group, an unknown stabilizer, an unknown or out-of-range controller key, a flywheel file without the arm
// trajectory) is refused with exit code 2, a message naming the file/key, and no log written; a short run with
// --json ends with one JSON object carrying the fields.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cstdio>
#include <filesystem>

#include "data/primitive_io.hpp"
#include "support/cli_run.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;

namespace {

using centaur_test::CliRun;
using centaur_test::run;

}  // namespace

TEST(SimulateJumpCli, BadInputIsRefusedWithoutOutput) {
  centaur_test::TempDir dir;
  const std::string log = (dir.path() / "log.h5").string();
  const std::string prims = (dir.path() / "prims.h5").string();
  // a primitive file that holds only the squat jump (planned by the CLI itself)
  ASSERT_EQ(run("plan squat-jump --quiet --out " + prims).code, 0);
  struct Case {
    std::string args;
    std::string must_contain;
  };
  const std::vector<Case> cases = {
      {"squat-jump --primitive " + (dir.path() / "none.h5").string(), "none.h5"},
      {"half-squat-jump --primitive " + prims, "half-squat-jump"},
      {"squat-jump --primitive " + prims + " --stabilizer magic", "magic"},
      {"squat-jump --primitive " + prims + " --set controller.bogus=1", "controller.bogus"},
      {"squat-jump --primitive " + prims + " --set controller.settle_time=99", "controller.settle_time"},
      {"squat-jump --primitive " + prims + " --set controller.raibert.gains=[1,2]", "controller.raibert.gains"},
      {"squat-jump --primitive " + prims + " --stabilizer ocp --flywheel " + prims, "arm-flywheel"},
  };
  for (const Case& c : cases) {
    const CliRun r = run("simulate " + c.args + " --out " + log);
    EXPECT_EQ(r.code, 2) << c.args << "\n" << r.out;
    EXPECT_NE(r.out.find(c.must_contain), std::string::npos) << "missing '" << c.must_contain << "' in: " << r.out;
    EXPECT_FALSE(fs::exists(log)) << c.args;
  }
}

TEST(SimulateJumpCli, JsonSummaryCarriesTheJumpFields) {
  centaur_test::TempDir dir;
  const std::string prims = (dir.path() / "prims.h5").string();
  ASSERT_EQ(run("plan half-squat-jump --quiet --out " + prims).code, 0);
  const CliRun r = run("simulate half-squat-jump --primitive " + prims + " --stabilizer raibert --duration 0.3 --json");
  ASSERT_EQ(r.code, 0) << r.out;
  const std::string last = r.out.substr(r.out.rfind('{'));
  const auto j = nlohmann::json::parse(last);
  for (const char* key : {"outcome", "peak_pitch_deg", "pitch_rms_deg", "max_torque_ratio", "wall_contact_s"}) {
    EXPECT_TRUE(j.contains(key)) << key << " missing in " << last;
  }
  EXPECT_EQ(j["outcome"], "no_wall_contact");  // 0.3 s: still settling, the rear wheels never left the ground
  // Timing: the controller's tick is a part of the control period, and the medians agree with the mean speed
  // within the spread of a shared machine (the real-time factor is 1 ms over the mean period).
  const double period_us = j.at("period_time_us_median"), tick_us = j.at("tick_time_us_median");
  EXPECT_GT(tick_us, 0.0);
  EXPECT_LT(tick_us, period_us);
  const double mean_period_us = 1e3 / j.at("real_time_factor").get<double>();
  EXPECT_LT(period_us, 1.5 * mean_period_us);
}
