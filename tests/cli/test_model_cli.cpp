// `centaur model check`: every shipped robot checks (exit 0, JSON with the derived template), a broken one
// exits 2 with the file and key named and nothing written, an unknown name lists the shipped robots.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>

#include "robot/robot_registry.hpp"
#include "support/cli_run.hpp"
#include "support/temp_dir.hpp"

namespace {

using centaur_test::run;

TEST(ModelCheckCli, EveryShippedRobotChecksAndReportsItsTemplate) {
  const auto names = centaur::robot::robotNames();
  ASSERT_GE(names.size(), 3u);
  for (const auto& name : names) {
    const auto r = run("model check " + name + " --json", false);
    ASSERT_EQ(r.code, 0) << name << "\n" << r.out;
    const auto j = nlohmann::json::parse(r.last_line);
    EXPECT_EQ(j["robot"], name);
    EXPECT_TRUE(j["ok"].get<bool>());
    EXPECT_EQ(j["hash"].get<std::string>().size(), 16u);
    const auto& t = j["derived"]["template"];
    // The template lumps the whole robot: waist + four feet = the MJCF's total mass.
    EXPECT_NEAR(t["waist_mass"].get<double>() + 4.0 * t["foot_mass"].get<double>(),
                j["derived"]["total_mass_kg"].get<double>(), 1e-9)
        << name;
    EXPECT_EQ(j["derived"]["feet"].size(), 4u);
  }
}

TEST(ModelCheckCli, BrokenDescriptionExitsTwoNamingFileAndKey) {
  centaur_test::TempDir dir{"centaur-model-cli"};
  std::ifstream in(std::string(CENTAUR_SOURCE_DIR) + "/models/centauro/robot.yaml");
  std::string yaml((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string from = "mjcf: centauro.xml", to = "mjcf: " + std::string(CENTAUR_SOURCE_DIR) + "/models/centauro/centauro.xml";
  yaml.replace(yaml.find(from), from.size(), to);
  const std::string good = yaml;
  yaml.replace(yaml.find("root: hip1_3"), 12, "root: hip9_3");
  std::ofstream(dir.file("robot.yaml")) << yaml;
  const auto before = dir.entries();
  const auto r = run("model check " + dir.path().string());
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find(dir.file("robot.yaml") + ": key 'feet.RL.root': no body 'hip9_3'"), std::string::npos) << r.out;
  EXPECT_EQ(dir.entries(), before);
  // The same folder repaired checks: the MJCF path resolves from robot.yaml, absolute or relative.
  std::ofstream(dir.file("robot.yaml")) << good;
  EXPECT_EQ(run("model check " + dir.file("robot.yaml")).code, 0);
}

TEST(ModelCheckCli, UnknownRobotListsTheShippedOnes) {
  const auto r = run("model check no-such-robot");
  EXPECT_EQ(r.code, 2);
  for (const auto& name : centaur::robot::robotNames()) EXPECT_NE(r.out.find(name), std::string::npos) << r.out;
}

}  // namespace

namespace {

TEST(ModelImportCli, CentauroUrdfBecomesARobotThatChecks) {
  const std::string urdf = std::string(CENTAUR_SOURCE_DIR) + "/../shared/reference/centauro/centauro.urdf";
  if (!std::ifstream(urdf)) GTEST_SKIP() << "no reference URDF at " << urdf;
  centaur_test::TempDir dir{"centaur-import-cli"};
  const auto r = run("model import " + urdf + " --out " + dir.file("centauro") + " --json", false);
  ASSERT_EQ(r.code, 0) << r.out;
  const auto j = nlohmann::json::parse(r.last_line);
  EXPECT_EQ(j["joints"], 39);
  EXPECT_NEAR(j["total_mass_kg"].get<double>(), 93.113, 0.001 * 93.113);
  EXPECT_TRUE(j["ok"].get<bool>()) << r.last_line;
  EXPECT_EQ(run("model check " + dir.file("centauro")).code, 0);
}

TEST(ModelImportCli, MissingUrdfExitsTwoAndWritesNothing) {
  centaur_test::TempDir dir{"centaur-import-cli"};
  const auto r = run("model import " + dir.file("none.urdf") + " --out " + dir.file("out"));
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find(dir.file("none.urdf")), std::string::npos) << r.out;
  EXPECT_TRUE(dir.entries().empty());
}

}  // namespace

namespace {

TEST(RobotCli, APrimitivePlannedForAnotherRobotIsRefusedNamingBoth) {
  centaur_test::TempDir dir{"centaur-robot-cli"};
  const auto plan = run("plan squat-jump --set robot=b2w_z1 --out " + dir.file("b2w.h5") + " --json", false);
  ASSERT_EQ(plan.code, 0) << plan.out;
  const auto r = run("simulate squat-jump --primitive " + dir.file("b2w.h5") + " --out " + dir.file("log.h5"));
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("planned for robot 'b2w_z1'"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("drives robot 'centauro'"), std::string::npos) << r.out;
  EXPECT_FALSE(std::ifstream(dir.file("log.h5")));
}

}  // namespace
