// ctest-labels: integration cli
// `centaur plan`: bad input is refused with exit code 2, a message naming file, key and range, and no output
// file; a solver that stops early exits 3 with the file written and flagged; --json ends with one object.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "data/primitive_io.hpp"
#include "support/cli_run.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;

namespace {

using centaur_test::CliRun;
using centaur_test::run;

std::string writeFile(const fs::path& p, const std::string& text) {
  std::ofstream(p) << text;
  return p.string();
}

void expectRefused(const std::string& args, const fs::path& out, const std::vector<std::string>& must_contain) {
  const CliRun r = run(args);
  EXPECT_EQ(r.code, 2) << r.out;
  for (const auto& s : must_contain) EXPECT_NE(r.out.find(s), std::string::npos) << "missing '" << s << "' in: " << r.out;
  EXPECT_FALSE(fs::exists(out)) << "an output file was left behind";
  for (const auto& e : fs::directory_iterator(out.parent_path())) {
    EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << "temporary file left: " << e.path();
  }
}

}  // namespace

TEST(PlanCli, MalformedYamlIsBadInput) {
  const centaur_test::TempDir tmp("centaur-plan-cli");
  const fs::path d = tmp.path(), out = d / "a.h5";
  const std::string cfg = writeFile(d / "bad.yaml", "horizon: {intervals: 30\ncost: [\n");
  expectRefused("plan squat-jump --config " + cfg + " --out " + out.string(), out, {"bad.yaml", "line"});
}

TEST(PlanCli, UnknownKeyIsBadInput) {
  const centaur_test::TempDir tmp("centaur-plan-cli");
  const fs::path d = tmp.path(), out = d / "b.h5";
  const std::string cfg = writeFile(d / "typo.yaml", "horizon:\n  intervalz: 30\n");
  expectRefused("plan squat-jump --config " + cfg + " --out " + out.string(), out, {"typo.yaml", "horizon.intervalz"});
}

TEST(PlanCli, NegativeMassIsBadInput) {
  const centaur_test::TempDir tmp("centaur-plan-cli");
  const fs::path d = tmp.path(), out = d / "c.h5";
  expectRefused("plan squat-jump --set model.waist_mass=-3 --out " + out.string(), out, {"model.waist_mass", "[0.001, 1000]"});
}

TEST(PlanCli, ReversedStepBoundsAreBadInput) {
  const centaur_test::TempDir tmp("centaur-plan-cli");
  const fs::path d = tmp.path(), out = d / "d.h5";
  expectRefused("plan squat-jump --set horizon.dt_min=0.2 --set horizon.dt_max=0.05 --out " + out.string(), out,
                {"horizon.dt_min", "dt_max"});
}

TEST(PlanCli, UnreachableTargetIsBadInput) {
  const centaur_test::TempDir tmp("centaur-plan-cli");
  const fs::path d = tmp.path(), out = d / "e.h5";
  expectRefused("plan squat-jump --set target.height=5 --out " + out.string(), out, {"target.height", "unreachable"});
}

TEST(PlanCli, SolverStoppedEarlyExits3WithTheFileFlagged) {
  const centaur_test::TempDir tmp("centaur-plan-cli");
  const fs::path d = tmp.path(), out = d / "f.h5";
  const CliRun r = run("plan squat-jump --quiet --json --set solver.max_iter=3 --out " + out.string());
  EXPECT_EQ(r.code, 3) << r.out;
  ASSERT_TRUE(fs::exists(out));
  const auto p = centaur::data::readPrimitive(out.string(), "squat-jump");
  EXPECT_EQ(p.solve.status, "max_iterations");
  const std::string last = r.out.substr(r.out.rfind('{'));
  const auto j = nlohmann::json::parse(last);
  EXPECT_EQ(j["status"], "max_iterations");
  EXPECT_EQ(j["iterations"], 3);
  EXPECT_EQ(j["backend"], "ipopt");
  EXPECT_FALSE(j.contains("first_attempt"));
  for (const char* k : {"solve_time_s", "cost", "max_constraint_violation"}) EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_TRUE(fs::exists(d / "f.squat-jump.yaml")) << "effective configuration saved next to the output";
}

TEST(PlanCli, RiccatiBackendStoppedEarlyExits3WithTheFileFlagged) {
  const centaur_test::TempDir tmp("centaur-plan-cli");
  const fs::path d = tmp.path(), out = d / "g.h5";
  const CliRun r = run("plan squat-jump --quiet --set solver.backend=riccati --set solver.max_iter=3 --out " + out.string());
  EXPECT_EQ(r.code, 3) << r.out;
  ASSERT_TRUE(fs::exists(out));
  const auto prim = centaur::data::readPrimitive(out.string(), "squat-jump");
  EXPECT_EQ(prim.solve.status, "max_iterations");
  EXPECT_EQ(prim.solve.backend, "riccati");
}

// solver.backend auto: riccati stops early, then Ipopt from the same start stops early too. The JSON says which
// backend produced the file and how riccati's attempt ended; both attempts' iteration limits are max_iter.
TEST(PlanCli, AutoBackendReportsRiccatisAttemptAndIpoptsResult) {
  const centaur_test::TempDir tmp("centaur-plan-cli");
  const fs::path d = tmp.path(), out = d / "a.h5";
  const CliRun r =
      run("plan squat-jump --quiet --json --set solver.backend=auto --set solver.max_iter=3 --out " + out.string());
  EXPECT_EQ(r.code, 3) << r.out;
  ASSERT_TRUE(fs::exists(out));
  const auto prim = centaur::data::readPrimitive(out.string(), "squat-jump");
  EXPECT_EQ(prim.solve.status, "max_iterations");
  EXPECT_EQ(prim.solve.backend, "ipopt") << "the file records the backend that produced it";
  const auto j = nlohmann::json::parse(r.out.substr(r.out.rfind("\n{") + 1));
  EXPECT_EQ(j["backend"], "ipopt");
  EXPECT_EQ(j["iterations"], 3);
  ASSERT_TRUE(j.contains("first_attempt")) << r.out;
  EXPECT_EQ(j["first_attempt"]["backend"], "riccati");
  EXPECT_EQ(j["first_attempt"]["status"], "max_iterations");
  EXPECT_EQ(j["first_attempt"]["iterations"], 3);
  EXPECT_LT(j["first_attempt"]["solve_time_s"].get<double>(), j["solve_time_s"].get<double>());
}

// The time limit covers both attempts of auto: riccati runs out of it, and Ipopt gets only what is left.
TEST(PlanCli, AutoBackendSharesOneTimeLimitBetweenItsAttempts) {
  const centaur_test::TempDir tmp("centaur-plan-cli");
  const fs::path out = tmp.path() / "t.h5";
  const CliRun r = run("plan squat-jump --quiet --json --set solver.backend=auto --set solver.max_cpu_time=0.05 --out " +
                       out.string());
  EXPECT_EQ(r.code, 3) << r.out;
  const auto j = nlohmann::json::parse(r.out.substr(r.out.rfind("\n{") + 1));
  EXPECT_EQ(j["first_attempt"]["status"], "max_cpu_time");
  EXPECT_EQ(j["status"], "max_cpu_time");
  EXPECT_EQ(j["backend"], "ipopt");
}

TEST(PlanCli, WarmStartFromAMissingFileGroupOrOtherHorizonIsBadInput) {
  const centaur_test::TempDir tmp("centaur-plan-cli");
  const fs::path d = tmp.path(), out = d / "h.h5", neighbour = d / "short.h5";
  expectRefused("plan squat-jump --warm-start " + (d / "missing.h5").string() + " --out " + out.string(), out,
                {"missing.h5"});
  // A neighbour planned on 12 intervals (stopped early: only its knots matter here).
  const CliRun w = run("plan squat-jump --quiet --set solver.max_iter=1 --set horizon.intervals=12 "
                       "--set horizon.takeoff=4 --set horizon.landing=8 --out " + neighbour.string());
  ASSERT_EQ(w.code, 3) << w.out;
  expectRefused("plan squat-jump --warm-start " + neighbour.string() + " --out " + out.string(), out,
                {"short.h5", "12 intervals"});
  expectRefused("plan squat-jump --warm-start " + neighbour.string() + ":nope --out " + out.string(), out,
                {"short.h5", "nope"});
  expectRefused("plan arm-flywheel --warm-start " + neighbour.string() + " --out " + out.string(), out,
                {"--warm-start"});
  // Re-planning into the file the warm start comes from would replace its primitives: refused, the file kept
  // (with --append that file is updated in place by design).
  const auto before = fs::last_write_time(neighbour);
  const CliRun same = run("plan squat-jump --warm-start " + neighbour.string() + " --out " + neighbour.string());
  EXPECT_EQ(same.code, 2) << same.out;
  EXPECT_NE(same.out.find("--warm-start"), std::string::npos) << same.out;
  EXPECT_EQ(fs::last_write_time(neighbour), before);
}
