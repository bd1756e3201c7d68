// ctest-labels: integration cli
// `centaur compare`: bad flags exit 2 before anything is written; a small comparison (squat jump, modes none
// and ocp, short runs) writes the documented files (a real PNG, the CSV it plots, md/JSON tables, the plans),
// ends --json with one object, and gives the same pitch histories on 1 and 2 threads (the full CENTAURO stack
// shares nothing between runs).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "support/cli_run.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;

namespace {

using centaur_test::CliRun;
using centaur_test::run;

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

TEST(CompareCli, BadFlagsExit2AndWriteNothing) {
  const centaur_test::TempDir dir("compare-cli-bad");
  const std::string out = dir.file("out");
  const std::string file = dir.file("a-file");
  std::ofstream(file) << "keep me\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--jumps stand", "not a jump scenario"},
      {"--jumps squat-jump,moon-jump", "moon-jump"},
      {"--modes none,magic", "magic"},
      {"--jumps squat-jump,squat-jump", "twice"},
      {"--set no_such_key=1", "no_such_key"},
      {"--set duration=-3", "duration"},
      {"--jobs -1", "--jobs"},
      {"--primitives " + dir.file("missing.h5"), "missing.h5"},
      {"--primitives " + file, "a-file"},  // not an HDF5 primitive file
      {"--flywheel " + dir.file("no-arm.h5"), "no-arm.h5"},
      {"--flywheel " + file, "a-file"},  // not an arm-flywheel file
  };
  for (const auto& [args, expect] : cases) {
    const CliRun r = run("compare --out " + out + " " + args);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.out;
    EXPECT_NE(r.out.find(expect), std::string::npos) << args << ": message lacks '" << expect << "':\n" << r.out;
    EXPECT_FALSE(fs::exists(out)) << args << ": the output directory was created";
  }
  const CliRun r = run("compare --out " + file);
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("not a directory"), std::string::npos) << r.out;
  EXPECT_EQ(readFile(file), "keep me\n");
  EXPECT_EQ(dir.entries().size(), 1u) << "something was written next to the inputs";
}

TEST(CompareCli, SmallComparisonWritesTablesPlotAndCsvSameOnOneAndTwoThreads) {
  const centaur_test::TempDir dir("compare-cli");
  const std::string a = dir.file("two-threads"), b = dir.file("one-thread");
  const std::string common = " --jumps squat-jump --modes none,ocp --set duration=0.8 --json";
  const CliRun r = run("compare --out " + a + " --jobs 2" + common, false);
  ASSERT_EQ(r.code, 0) << r.out;

  for (const char* f : {"primitives.h5", "primitives.squat-jump.yaml", "arm-flywheel.h5", "squat-jump-none.h5",
                        "squat-jump-none.config.yaml", "squat-jump-ocp.h5", "squat-jump-ocp.config.yaml",
                        "compare.md", "compare.json", "compare-pitch.csv", "compare-pitch.png"}) {
    EXPECT_TRUE(fs::is_regular_file(fs::path(a) / f)) << f;
  }
  for (const auto& e : fs::directory_iterator(a)) {
    EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << "temporary file left: " << e.path();
  }

  // The plot is a PNG (signature, IHDR of the documented width).
  const std::string png = readFile((fs::path(a) / "compare-pitch.png").string());
  ASSERT_GT(png.size(), 1000u);
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_EQ(png.substr(12, 4), "IHDR");
  const auto width = (static_cast<unsigned char>(png[16]) << 24) | (static_cast<unsigned char>(png[17]) << 16) |
                     (static_cast<unsigned char>(png[18]) << 8) | static_cast<unsigned char>(png[19]);
  EXPECT_EQ(width, 1100);

  // --json: one object on the last line, runs as in compare.json, every listed file exists.
  const nlohmann::json j = nlohmann::json::parse(r.last_line);
  ASSERT_TRUE(j.contains("runs") && j.contains("files") && j.contains("wall_time_s")) << j.dump();
  ASSERT_EQ(j["runs"].size(), 2u);
  EXPECT_EQ(j["runs"], nlohmann::json::parse(readFile((fs::path(a) / "compare.json").string())));
  for (const auto& f : j["files"]) EXPECT_TRUE(fs::exists(f.get<std::string>())) << f;
  for (std::size_t i = 0; i < 2; ++i) {
    const auto& run_j = j["runs"][i];
    EXPECT_EQ(run_j["scenario"], "squat-jump");
    EXPECT_EQ(run_j["stabilizer"], i == 0 ? "none" : "ocp");
    EXPECT_TRUE(run_j["outcome"].is_string());
    EXPECT_NEAR(run_j["duration_s"].get<double>(), 0.8, 1e-6);
    for (const char* k : {"peak_pitch_deg", "pitch_rms_deg", "max_torque_ratio", "real_time_factor"}) {
      ASSERT_TRUE(run_j[k].is_number()) << k;
      EXPECT_GE(run_j[k].get<double>(), 0.0) << k;
    }
  }
  const std::string md = readFile((fs::path(a) / "compare.md").string());
  EXPECT_NE(md.find("| squat-jump | none | "), std::string::npos) << md;
  EXPECT_NE(md.find("| squat-jump | ocp | "), std::string::npos) << md;
  // The ocp runs got the arm-flywheel trajectory planned once by compare.
  EXPECT_EQ(j["flywheel"], (fs::path(a) / "arm-flywheel.h5").string());

  // CSV: time plus one column per run, one row per control period.
  const std::string csv = readFile((fs::path(a) / "compare-pitch.csv").string());
  std::istringstream lines(csv);
  std::string header;
  std::getline(lines, header);
  EXPECT_EQ(header, "t_s,squat-jump/none,squat-jump/ocp");
  std::size_t rows = 0;
  for (std::string l; std::getline(lines, l);) ++rows;
  EXPECT_EQ(rows, 800u);

  // The same runs one at a time (plans reused): the same pitch histories, to the printed digit.
  const CliRun r1 = run("compare --out " + b + " --jobs 1 --primitives " + (fs::path(a) / "primitives.h5").string() +
                            " --flywheel " + (fs::path(a) / "arm-flywheel.h5").string() + common,
                        false);
  ASSERT_EQ(r1.code, 0) << r1.out;
  EXPECT_FALSE(fs::exists(fs::path(b) / "primitives.h5")) << "--primitives must not plan again";
  EXPECT_FALSE(fs::exists(fs::path(b) / "arm-flywheel.h5")) << "--flywheel must not plan again";
  EXPECT_EQ(readFile((fs::path(b) / "compare-pitch.csv").string()), csv);
}
