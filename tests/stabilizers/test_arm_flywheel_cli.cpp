// ctest-labels: integration cli
// `centaur plan arm-flywheel`: writes the HDF5 group and the effective configuration next to it, --json ends
// with one object; a bad configuration key exits 2 naming the key and writes nothing; a solver stopped early
// exits 3 with the file written and flagged (solve_status), which the stabilizer then refuses.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cstdio>
#include <filesystem>

#include "common/error.hpp"
#include "data/arm_trajectory_io.hpp"
#include "stabilizers/ocp_posture_stabilizer.hpp"
#include "support/cli_run.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;

namespace {

using centaur_test::CliRun;
using centaur_test::run;

}  // namespace

TEST(ArmFlywheelCli, WritesTheTrajectoryAndPrintsJson) {
  centaur_test::TempDir dir;
  const std::string out = dir.file("flywheel.h5");
  const CliRun r = run("plan arm-flywheel --out " + out + " --json --quiet");
  ASSERT_EQ(r.code, 0) << r.out;
  const auto j = nlohmann::json::parse(r.last_line);
  EXPECT_EQ(j["primitive"], "arm-flywheel");
  EXPECT_EQ(j["status"], "solved");
  EXPECT_GT(j["iterations"].get<int>(), 0);
  EXPECT_GT(j["h_y_mean_Nms"].get<double>(), 1.0);
  EXPECT_LE(j["max_torque_ratio"].get<double>(), 1.0);
  const auto tr = centaur::data::readArmTrajectory(out);
  EXPECT_EQ(tr.solve.status, "solved");
  EXPECT_EQ(tr.q.rows(), 1001);
  EXPECT_TRUE(fs::exists(dir.file("flywheel.arm-flywheel.yaml")));
  // the stabilizer loads it
  centaur::OcpPostureParams p;
  p.flywheel_file = out;
  EXPECT_NO_THROW(centaur::OcpPostureStabilizer{p});
}

TEST(ArmFlywheelCli, BadKeyExitsTwoWithoutWriting) {
  centaur_test::TempDir dir;
  const std::string out = dir.file("bad.h5");
  const CliRun r = run("plan arm-flywheel --out " + out + " --set cost.momentun=2");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("cost.momentun"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_TRUE(fs::is_empty(dir.path())) << "something was written";
  const CliRun range = run("plan arm-flywheel --out " + out + " --set horizon.intervals=1");
  EXPECT_EQ(range.code, 2) << range.out;
  EXPECT_NE(range.out.find("horizon.intervals"), std::string::npos) << range.out;
  EXPECT_FALSE(fs::exists(out));
}

TEST(ArmFlywheelCli, NotConvergedExitsThreeAndIsFlagged) {
  centaur_test::TempDir dir;
  const std::string out = dir.file("early.h5");
  const CliRun r = run("plan arm-flywheel --out " + out + " --set solver.max_iter=3 --quiet --json");
  EXPECT_EQ(r.code, 3) << r.out;
  ASSERT_TRUE(fs::exists(out));
  EXPECT_NE(centaur::data::readArmTrajectory(out).solve.status, "solved");
  centaur::OcpPostureParams p;
  p.flywheel_file = out;
  EXPECT_THROW(centaur::OcpPostureStabilizer{p}, centaur::InputError);
}
