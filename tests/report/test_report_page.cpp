// ctest-labels: unit
// The page `centaur report` writes, from a synthetic CENTAURO log and plan: one self-contained HTML file (CSP that
// forbids every network request, the data in one JSON script element that nothing in it can close, the viewer
// inline); body poses at the pose rate decoding to the log's pelvis within micrometres; the plan's ghost on the
// robot's clock (t0 = controller.settle_time); the simulator's summary as metadata; a plan alone; bad input
// refused before anything is written.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "data/primitive_io.hpp"
#include "data/sim_log_file.hpp"
#include "model/chain_from_mjcf.hpp"
#include "report/channel_codec.hpp"
#include "report/kinematic_model.hpp"
#include "report/report.hpp"
#include "report/viewer_asset.hpp"
#include "support/synthetic_primitive.hpp"
#include "support/temp_dir.hpp"

namespace report = centaur::report;
namespace data = centaur::data;

namespace {

constexpr double kDt = 0.001, kDuration = 1.5, kSettle = 0.25;

double pelvisZ(double t) { return 0.72 + 0.2 * std::sin(2.0 * t); }

/// A 1.5 s CENTAURO log at 1 kHz: joints at zero, the pelvis moving up and down, 200 N on each wheel.
void writeSyntheticLog(const std::string& path, const std::vector<std::string>& joints, bool summary) {
  data::SimLogHeader h;
  h.joint_names = joints;
  h.contact_bodies = {"wheel_1", "wheel_2", "wheel_3", "wheel_4"};
  h.config_yaml = "model: \"\"\nworld: {wall_x: -0.6}\ncontroller: {settle_time: 0.25}\n"
                  "note: \"</script><!-- <script>alert(1)</script>\"\n";
  h.scenario = "squat-jump";
  if (summary) h.summary_json = R"({"outcome":"success","peak_pitch_deg":4.5,"pitch_rms_deg":1.25})";
  h.samples = static_cast<std::size_t>(std::lround(kDuration / kDt)) + 1;
  std::map<std::string, std::vector<double>> v;
  for (const data::LogDataset& d : data::simLogDatasets()) {
    std::size_t count = 1;
    for (auto x : data::logDatasetDims(d, h)) count *= x;
    v[d.name].assign(count, 0.0);
  }
  for (std::size_t i = 0; i < h.samples; ++i) {
    const double t = static_cast<double>(i) * kDt;
    v["t"][i] = t;
    v["base_pos"][3 * i + 2] = pelvisZ(t);
    v["base_quat"][4 * i] = v["imu_quat"][4 * i] = 1.0;
    for (int k = 0; k < 4; ++k) v["wheel_force"][12 * i + 3 * k + 2] = 200.0;
    v["tau_applied"][joints.size() * i] = 10.0 * std::sin(t);
  }
  std::map<std::string, const std::vector<double>*> ptr;
  for (const auto& [k, x] : v) ptr[k] = &x;
  data::writeSimLog(path, h, ptr);
}

std::vector<std::string> centauroJoints() {
  report::KinematicModel km(centaur::model::centauroMjcfPath());
  std::vector<std::string> names;
  for (int a = 0; a < km.model()->nu; ++a) {
    names.emplace_back(mj_id2name(km.model(), mjOBJ_JOINT, km.model()->actuator_trnid[2 * a]));
  }
  return names;
}

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// The page's JSON (between the data script element's tags).
nlohmann::json pageData(const std::string& page) {
  const std::string open = "<script type=\"application/json\" id=\"centaur-report-data\">";
  const std::size_t a = page.find(open);
  const std::size_t b = page.find("</script>", a);
  EXPECT_NE(a, std::string::npos);
  return nlohmann::json::parse(page.substr(a + open.size(), b - a - open.size()));
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
  return n;
}

}  // namespace

TEST(ReportPage, SelfContainedPageWithPosesGhostPlotsAndMetadata) {
  const centaur_test::TempDir dir("report-page");
  const std::string log = dir.file("run.h5"), prim = dir.file("plan.h5"), html = dir.file("out/run.html");
  writeSyntheticLog(log, centauroJoints(), true);
  const data::Primitive plan = centaur::test::makeSyntheticJump("squat-jump");
  data::writePrimitive(prim, plan);
  const report::ReportStats stats = report::writeReport(html, report::runSources({log}, prim, ""), {});
  const std::string page = readFile(html);
  EXPECT_EQ(stats.bytes, page.size());
  EXPECT_EQ(stats.frames, 151u);  // 1.5 s at 100 Hz, both ends

  EXPECT_NE(page.find("Content-Security-Policy\" content=\"default-src 'none'"), std::string::npos);
  EXPECT_EQ(count(page, "<script"), 2u);   // the data and the viewer; the config's "<script>" is escaped
  EXPECT_EQ(count(page, "</script"), 2u);
  EXPECT_EQ(count(page, "<!--"), 0u);
  EXPECT_NE(page.find(std::string(report::viewerScript().substr(0, 200))), std::string::npos);
  // (the viewer's code holds namespace URIs such as http://www.w3.org/2000/svg; the browser test proves that the
  // page requests nothing)

  const nlohmann::json d = pageData(page);
  EXPECT_EQ(d["format"], "centaur-report 1");
  EXPECT_EQ(d["viewer"], std::string(report::viewerScriptSha256()));
  ASSERT_EQ(d["runs"].size(), 1u);
  const nlohmann::json& run = d["runs"][0];
  EXPECT_NE(run["config_yaml"].get<std::string>().find("</script><!--"), std::string::npos);  // intact once parsed
  const std::vector<std::uint8_t> tb = report::decodeBase64(run["frames"]["t"].get<std::string>());
  const std::vector<double> pose = report::decodeInt16Channels(run["frames"]["pose"]);
  const std::size_t stride = run["frames"]["pose"]["channels"];
  ASSERT_EQ(tb.size(), 4u * 151u);
  for (std::size_t k = 0; k < 151; ++k) {
    float t;
    std::memcpy(&t, tb.data() + 4 * k, 4);
    EXPECT_NEAR(t, 0.01 * static_cast<double>(k), 1e-6);
    EXPECT_NEAR(pose[k * stride + 2], pelvisZ(0.01 * static_cast<double>(k)), 5e-6) << "frame " << k;
  }
  // ghost: the plan on the robot's clock, starting at controller.settle_time
  EXPECT_EQ(run["ghost"]["t0"], kSettle);
  const std::vector<double> ghost = report::decodeInt16Channels(run["ghost"]["pose"]);
  ASSERT_EQ(run["ghost"]["frames"], 101u);
  for (std::size_t k = 0; k < 101; k += 10) {
    EXPECT_NEAR(ghost[31 * k + 2], plan.base_pos(static_cast<Eigen::Index>(10 * k), 2), 5e-6);
    EXPECT_NEAR(ghost[31 * k + 19 + 2], plan.force(static_cast<Eigen::Index>(10 * k), 2), 0.05);
  }
  EXPECT_EQ(run["plan"]["solve_status"], plan.solve.status);
  // plots: pitch (IMU + planned), force (4 measured + 4 planned), torque (the one loaded joint)
  ASSERT_EQ(run["plots"].size(), 3u);
  EXPECT_EQ(run["plots"][0]["series"].size(), 2u);
  EXPECT_EQ(run["plots"][1]["series"].size(), 8u);
  EXPECT_EQ(run["plots"][2]["series"].size(), 1u);
  EXPECT_EQ(run["plots"][2]["series"][0]["label"], "torso_yaw");
  // metadata from the simulator's summary; the wall where world.wall_x put it
  EXPECT_EQ(run["metrics"]["source"], "simulator");
  EXPECT_EQ(run["metrics"]["items"][0]["value"], "success");
  const auto& bodies = d["scene"]["bodies"];
  const std::size_t wall = static_cast<std::size_t>(std::find(bodies.begin(), bodies.end(), "wall") - bodies.begin());
  const std::size_t static_slot = wall - d["scene"]["moving"].get<std::size_t>();
  EXPECT_NEAR(run["static_pose"][7 * static_slot].get<double>(), -0.6, 1e-12);
}

TEST(ReportPage, ALogWithoutSummaryGetsMetricsFromItsDatasets) {
  const centaur_test::TempDir dir("report-nosummary");
  const std::string log = dir.file("run.h5"), html = dir.file("run.html");
  writeSyntheticLog(log, centauroJoints(), false);
  report::writeReport(html, report::runSources({log}, "", ""), {});
  const nlohmann::json run = pageData(readFile(html))["runs"][0];
  EXPECT_EQ(run["metrics"]["source"], "log");
  EXPECT_TRUE(run["ghost"].is_null());
  std::map<std::string, nlohmann::json> m;
  for (const auto& it : run["metrics"]["items"]) m[it["key"]] = it["value"];
  EXPECT_NEAR(m["peak_pitch_deg"].get<double>(), 0.0, 1e-12);  // upright all along
  EXPECT_NEAR(m["max_torque_ratio"].get<double>(), 10.0 * std::sin(1.5) / 147.0, 1e-2);  // torso_yaw: 147 N m
}

TEST(ReportPage, APlanAloneShowsEachPrimitiveOfTheFile) {
  const centaur_test::TempDir dir("report-plan");
  const std::string prim = dir.file("plans.h5"), html = dir.file("plans.html");
  data::writePrimitives(prim, {centaur::test::makeSyntheticJump("squat-jump"),
                               centaur::test::makeSyntheticJump("half-squat-jump", 0.5)});
  report::writeReport(html, report::runSources({}, prim, ""), {});
  const nlohmann::json d = pageData(readFile(html));
  ASSERT_EQ(d["runs"].size(), 2u);
  for (const auto& run : d["runs"]) {
    EXPECT_EQ(run["kind"], "plan");
    EXPECT_TRUE(run["frames"].is_null());
    EXPECT_EQ(run["ghost"]["t0"], 0.0);
    EXPECT_EQ(run["plots"].size(), 3u);
  }
  EXPECT_EQ(d["runs"][1]["scenario"], "half-squat-jump");
}

TEST(ReportPage, BadInputIsRefusedBeforeAnythingIsWritten) {
  const centaur_test::TempDir dir("report-bad");
  const std::string log = dir.file("run.h5"), prim = dir.file("plan.h5"), html = dir.file("out.html");
  std::vector<std::string> joints = centauroJoints();
  writeSyntheticLog(log, joints, true);
  data::writePrimitive(prim, centaur::test::makeSyntheticJump("other-jump"));
  data::writePrimitive(dir.file("two.h5"), centaur::test::makeSyntheticJump("a"));
  data::writePrimitive(dir.file("two.h5"), centaur::test::makeSyntheticJump("b"), data::WriteMode::Append);
  joints[3] = "j_arm9_9";
  writeSyntheticLog(dir.file("foreign.h5"), joints, true);
  auto expectRefused = [&](const std::vector<report::RunSource>& runs, const report::ReportOptions& o,
                           std::vector<std::string> words) {
    try {
      report::writeReport(html, runs, o);
      ADD_FAILURE() << "no InputError";
    } catch (const centaur::InputError& e) {
      for (const auto& w : words) EXPECT_NE(std::string(e.what()).find(w), std::string::npos) << e.what();
    }
    EXPECT_FALSE(std::filesystem::exists(html));
  };
  report::ReportOptions slow;
  slow.pose_rate_hz = 5.0;
  expectRefused({{"", log, "", ""}}, slow, {"--rate"});
  expectRefused({{"", prim, "", ""}}, {}, {"plan.h5", "format"});                 // a primitive file as a log
  expectRefused({{"", dir.file("foreign.h5"), "", ""}}, {}, {"foreign.h5", "joint_names", "j_arm9_9"});
  expectRefused({{"", log, dir.file("two.h5"), ""}}, {}, {"two.h5", "squat-jump", "a, b"});  // which plan?
  expectRefused({}, {}, {"nothing to show"});
  EXPECT_EQ(dir.entries().size(), 4u) << "a temporary or partial file was left";
}
