// ctest-labels: browser integration
// The report pages in a real browser: Debian's chromium, headless, driven by playwright-core (web/test/probe.cjs,
// one launch for every page). From a real squat jump (planned, then simulated 2.6 s: through the flight), a small
// comparison (2 runs) and the plan alone: no console error, no network request, the WebGL canvas is not blank,
// seeking to the flight phase changes the picture and puts the pelvis where the log has it (1 mm), the ghost
// where the plan has it, the pitch cursor follows the replay, a click in a plot seeks, the run selector switches
// runs. Screenshots are
// kept in <build>/tests/report/artifacts/.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "data/primitive_io.hpp"
#include "data/sim_log_file.hpp"
#include "support/cli_run.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;
namespace data = centaur::data;
using centaur_test::run;

namespace {

constexpr double kMm = 1e-3;
constexpr double kDuration = 2.6;  // [s] through the planned flight (robot time 1.93 - 2.20 s)

struct Log {
  Eigen::VectorXd t;
  data::RowMatrix pos, force;
  explicit Log(const std::string& path) {
    const data::SimLogFile f(path);
    t = f.time();
    pos = f.read("base_pos");
    force = f.read("wheel_force");
  }
  Eigen::Index row(double time) const {
    Eigen::Index best = 0;
    for (Eigen::Index i = 0; i < t.size(); ++i) {
      if (std::abs(t[i] - time) < std::abs(t[best] - time)) best = i;
    }
    return best;
  }
  /// Middle of the longest interval with every wheel's force under 1 N, on the 10 ms frame grid.
  double midFlight() const {
    double best = 0.0, best_len = 0.0, start = -1.0;
    for (Eigen::Index i = 0; i < t.size(); ++i) {
      bool air = true;
      for (Eigen::Index c = 0; c < force.cols(); c += 3) air = air && force.row(i).segment<3>(c).norm() < 1.0;
      if (air && start < 0.0) start = t[i];
      if (air && t[i] - start > best_len) {
        best_len = t[i] - start;
        best = 0.5 * (start + t[i]);
      }
      if (!air) start = -1.0;
    }
    EXPECT_GT(best_len, 0.1) << "the squat jump did not fly";
    return std::round(best * 100.0) / 100.0;
  }
};

std::vector<double> vec(const nlohmann::json& j) { return j.get<std::vector<double>>(); }

double thumbDifference(const nlohmann::json& a, const nlohmann::json& b) {
  const std::vector<double> x = vec(a["stats"]["thumb"]), y = vec(b["stats"]["thumb"]);
  double d = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) d += std::abs(x[i] - y[i]);
  return d / static_cast<double>(x.size());
}

nlohmann::json runProbe(const nlohmann::json& spec, const std::string& dir) {
  const std::string spec_path = dir + "/spec.json", result_path = dir + "/result.json";
  std::ofstream(spec_path) << spec.dump(1);
  const std::string cmd = std::string("NODE_PATH=") + CENTAUR_WEB_NODE_MODULES + " " + CENTAUR_NODE + " " +
                          CENTAUR_SOURCE_DIR + "/web/test/probe.cjs " + spec_path + " " + result_path + " 2>&1";
  const int status = std::system(cmd.c_str());
  EXPECT_EQ(status, 0) << cmd;
  std::ifstream in(result_path);
  return nlohmann::json::parse(in, nullptr, false);
}

}  // namespace

TEST(ReportBrowser, PagesOfARealSquatJumpAComparisonAndAPlan) {
  ASSERT_TRUE(fs::exists("/usr/bin/chromium")) << "Debian's chromium is missing: make deps installs it";
  const centaur_test::TempDir dir("report-browser");
  const std::string art = CENTAUR_REPORT_ARTIFACTS;
  fs::remove_all(art);
  fs::create_directories(art);
  const std::string plan = dir.file("plan.h5"), log = dir.file("jump.h5"), cmp = dir.file("compare");
  const std::string set = " --set duration=" + std::to_string(kDuration);
  ASSERT_EQ(run("plan squat-jump --out " + plan, false).code, 0);
  ASSERT_EQ(run("simulate squat-jump --primitive " + plan + " --stabilizer raibert --out " + log + set, false).code, 0);
  ASSERT_EQ(run("compare --out " + cmp + " --jumps squat-jump --modes none,raibert --primitives " + plan + set, false).code, 0);
  ASSERT_EQ(run("report " + log + " --primitive " + plan + " --out " + dir.file("jump.html"), false).code, 0);
  ASSERT_EQ(run("report --primitive " + plan + " --out " + dir.file("plan.html"), false).code, 0);
  ASSERT_TRUE(fs::exists(cmp + "/report.html"));

  const Log jump(log), none(cmp + "/squat-jump-none.h5"), raibert(cmp + "/squat-jump-raibert.h5");
  const double t_stand = 0.3, t_fly = jump.midFlight();
  // The comparison's runs differ most at t_diff: where the selector's switch must show.
  double t_diff = 0.0, diff = 0.0;
  for (double t = 0.0; t <= kDuration - 0.01; t += 0.01) {
    const double d = (none.pos.row(none.row(t)) - raibert.pos.row(raibert.row(t))).norm();
    if (d > diff) { diff = d; t_diff = std::round(t * 100.0) / 100.0; }
  }
  ASSERT_GT(diff, 2 * kMm) << "the two stabilizers' runs are too alike to tell apart";

  const nlohmann::json spec = {
      {"chromium", "/usr/bin/chromium"}, {"artifacts", art},
      {"pages", {{{"name", "jump"}, {"file", dir.file("jump.html")}, {"times", {t_stand, t_fly, t_fly + 0.005}},
                  {"screenshots", {{"stand", t_stand}, {"flight", t_fly}}}, {"play_from", 0.5}, {"play_seconds", 1.0},
                  {"click_plot", 0.75}},
                 {{"name", "compare"}, {"file", cmp + "/report.html"}, {"runs_switch", {{"times", {t_diff}}}}},
                 {{"name", "plan"}, {"file", dir.file("plan.html")}, {"times", {t_fly}},
                  {"screenshots", {{"flight", t_fly}}}}}}};
  const nlohmann::json result = runProbe(spec, art);
  ASSERT_TRUE(result.is_object() && result["pages"].size() == 3) << result.dump();

  for (const auto& page : result["pages"]) {  // every page: no error, no network, a picture
    SCOPED_TRACE(page["name"].get<std::string>());
    EXPECT_TRUE(page["console_errors"].empty()) << page["console_errors"].dump();
    EXPECT_TRUE(page["page_errors"].empty()) << page["page_errors"].dump();
    EXPECT_TRUE(page["requests"].empty()) << page["requests"].dump();
  }
  const nlohmann::json& p = result["pages"][0];
  const nlohmann::json &stand = p["probes"][0], &fly = p["probes"][1], &fly2 = p["probes"][2];
  // the canvas is drawn: luminance varies, a third of the thumbnail differs from the background
  EXPECT_GT(stand["stats"]["std"].get<double>(), 10.0);
  // seeking to the flight changes the picture and lifts the pelvis where the log has it
  EXPECT_GT(thumbDifference(stand, fly), 1.0);
  for (const auto* probe : {&fly, &fly2}) {
    const double t = (*probe)["t"];
    const std::vector<double> pelvis = vec((*probe)["pelvis"]);
    EXPECT_NEAR(pelvis[2], jump.pos(jump.row(t), 2), kMm) << "t = " << t;
    EXPECT_NEAR(pelvis[0], jump.pos(jump.row(t), 0), kMm) << "t = " << t;
  }
  EXPECT_GT(vec(fly["pelvis"])[2], vec(stand["pelvis"])[2] + 0.1);
  // the ghost is the plan at t - settle_time (0.5 s)
  const data::Primitive prim = data::readPrimitive(plan, "squat-jump");
  const Eigen::Index k = static_cast<Eigen::Index>(std::lround((t_fly - 0.5) / 0.001));
  EXPECT_NEAR(vec(fly["ghost"])[2], prim.base_pos(k, 2), kMm);
  // the pitch cursor moves with the replay: by seeking and by playing
  EXPECT_GT(fly["cursor_left"].get<double>(), stand["cursor_left"].get<double>() + 50.0);
  EXPECT_GT(p["play"]["after"]["time"].get<double>(), p["play"]["before"]["time"].get<double>() + 0.05);
  EXPECT_GT(p["play"]["after"]["cursor_left"].get<double>(), p["play"]["before"]["cursor_left"].get<double>() + 2.0);
  EXPECT_EQ(p["plots"], nlohmann::json({"pitch", "force", "torque"}));
  // a click at 3/4 of the pitch plot's width seeks to 3/4 of the run (the x axis spans the log's time range)
  const double t0 = p["click"]["range"][0], t1 = p["click"]["range"][1];
  EXPECT_NEAR(p["click"]["time"].get<double>(), t0 + 0.75 * (t1 - t0), 0.02 * (t1 - t0));
  EXPECT_NEAR(p["click"]["cursor_left"].get<double>(), 0.75 * p["click"]["width"].get<double>(), 3.0);

  // the comparison: two runs, the selector shows each run's own motion
  const nlohmann::json& c = result["pages"][1];
  ASSERT_EQ(c["runs"].size(), 2u);
  ASSERT_EQ(c["switch"].size(), 2u);
  const Log* logs[2] = {&none, &raibert};
  for (int i = 0; i < 2; ++i) {
    const nlohmann::json& s = c["switch"][i];
    EXPECT_EQ(s["run"], i);
    EXPECT_EQ(s["title"], c["runs"][i]);
    const std::vector<double> pelvis = vec(s["probes"][0]["pelvis"]);
    const Eigen::Index r = logs[i]->row(t_diff);
    EXPECT_LT((Eigen::Vector3d(pelvis[0], pelvis[1], pelvis[2]) - logs[i]->pos.row(r).transpose()).norm(), kMm)
        << "run " << i << " at t = " << t_diff;
  }
  EXPECT_NE(c["runs"][0].get<std::string>().find("none"), std::string::npos);

  // the plan alone: the ghost is the plan at t (its own clock), no robot
  const nlohmann::json& g = result["pages"][2]["probes"][0];
  EXPECT_TRUE(g["pelvis"].is_null());
  const Eigen::Index kp = static_cast<Eigen::Index>(std::lround(t_fly / 0.001));
  EXPECT_NEAR(vec(g["ghost"])[2], prim.base_pos(kp, 2), kMm);
  EXPECT_GT(g["stats"]["std"].get<double>(), 5.0);

  for (const char* f : {"jump-stand.png", "jump-flight.png", "compare-run0.png", "compare-run1.png", "plan-flight.png"}) {
    EXPECT_TRUE(fs::exists(art + "/" + f)) << f;
  }
}
