// Broken robot descriptions, one fault each: robot.yaml faults stop the reader with the file and key named
// (InputError); MJCF faults are listed by checkRobot() as problems naming the file (and the key), with no facts.
#include <gtest/gtest.h>

#include <functional>

#include "common/error.hpp"
#include "robot/robot_facts.hpp"
#include "robot/synthetic_robot.hpp"
#include "support/temp_dir.hpp"

namespace {

using centaur_test::syntheticMjcf;
using centaur_test::syntheticYaml;

std::string plainMjcf() { return syntheticMjcf(); }

std::string replaced(std::string s, const std::string& from, const std::string& to) {
  const auto at = s.find(from);
  if (at == std::string::npos) throw std::logic_error("test text has no '" + from + "'");
  return s.replace(at, from.size(), to);
}

struct Fault {
  const char* what;
  std::function<std::string()> yaml, mjcf;
  const char* file;     // "yaml" or "mjcf": which file the message names
  const char* key;      // the key named ("" = none expected)
  const char* message;  // a part of the message
};

const Fault kYamlFaults[] = {
    {"missing key", [] { return replaced(syntheticYaml(), "base: base\n", ""); }, plainMjcf, "yaml", "base", "is required"},
    {"unknown key", [] { return syntheticYaml() + "colour: red\n"; }, plainMjcf, "yaml", "", "colour"},
    {"three feet", [] { return replaced(syntheticYaml(), "  RR: {root: rr_hip, contact: rr_foot, centre: rr_centre, type: point, radius: auto}\n", ""); },
     plainMjcf, "yaml", "feet.RR", "exactly four feet"},
    {"nine-joint arm", [] { return replaced(syntheticYaml(), "joints: [left_j1, left_j2]", "joints: [a1, a2, a3, a4, a5, a6, a7, a8, a9]"); },
     plainMjcf, "yaml", "upper_body.arms[0].joints", "1 to 8 joints"},
    {"bad foot type", [] { return replaced(syntheticYaml(), "type: point, radius: auto}\n  FR", "type: hoof, radius: auto}\n  FR"); },
     plainMjcf, "yaml", "feet.FL.type", "wheel, point"},
    {"radius out of range", [] { return replaced(syntheticYaml(), "centre: rr_centre, type: point, radius: auto", "centre: rr_centre, type: point, radius: 3"); },
     plainMjcf, "yaml", "feet.RR.radius", "[0.001, 1]"},
    {"mirror of nothing", [] { return replaced(syntheticYaml(), "mirrors: left", "mirrors: middle"); }, plainMjcf, "yaml",
     "upper_body.arms[1].mirrors", "names no other arm"},
    {"negative gain", [] { return replaced(syntheticYaml(), "kp: 100.0", "kp: -1"); }, plainMjcf, "yaml", "gains[0].kp", ""},
};

const Fault kModelFaults[] = {
    {"wrong body name", [] { return replaced(syntheticYaml(), "root: fl_hip", "root: fl_hips"); }, plainMjcf, "yaml",
     "feet.FL.root", "no body 'fl_hips'"},
    {"missing IMU sensor", syntheticYaml, [] { return replaced(syntheticMjcf(), "<gyro name=\"imu_gyro\" site=\"imu\"/>", ""); },
     "yaml", "imu.gyro", "no sensor 'imu_gyro'"},
    {"position actuator", syntheticYaml, [] { return syntheticMjcf("position"); }, "mjcf", "", "not a torque motor"},
    {"unsupported feature", syntheticYaml,
     [] { return replaced(syntheticMjcf(), "range=\"-3 3\"/>", "range=\"-3 3\" actuatorfrcrange=\"-1 1\"/>"); }, "mjcf", "",
     "MuJoCo 2.2.2 does not load"},
    {"no free joint", syntheticYaml, [] { return replaced(replaced(syntheticMjcf(), "<freejoint name=\"root\"/>", ""), "0 0 0.45 1 0 0 0 ", ""); }, "mjcf", "", "no free joint"},
    {"joint without limits", syntheticYaml, [] { return replaced(syntheticMjcf(), "axis=\"0 1 0\" range=\"-2 2\" user", "axis=\"0 1 0\" user"); },
     "mjcf", "", "has no range"},
    {"stabilizer joint not in an arm", [] { return replaced(syntheticYaml(), "raibert: [left_j1, right_j1]", "raibert: [fl_pitch]"); },
     plainMjcf, "yaml", "stabilizers.raibert", "not a joint of an arm"},
    {"feet off the ground", syntheticYaml, [] { return replaced(syntheticMjcf(), "qpos=\"0 0 0.45 ", "qpos=\"0 0 0.55 "); }, "yaml",
     "home", "not the ground"},
    {"arms not mirrored", syntheticYaml, [] { return replaced(syntheticMjcf(), "<body name=\"right1\" pos=\"0 -0.300000 0.1\">", "<body name=\"right1\" pos=\"0 -0.2 0.1\">"); },
     "yaml", "upper_body.arms[1].mirrors", "not the sagittal mirror image"},
    {"gains miss a joint", [] { return replaced(syntheticYaml(), "joints: [\"*\"]", "joints: [\"left_*\"]"); }, plainMjcf, "yaml",
     "gains", "'right_j1' matches no group"},
};

void PrintTo(const Fault& f, std::ostream* os) { *os << f.what; }

class BrokenDescription : public ::testing::TestWithParam<Fault> {
 protected:
  std::string write(const Fault& f) {
    centaur_test::writeText(dir.file("synthetic.xml"), f.mjcf());
    centaur_test::writeText(dir.file("robot.yaml"), f.yaml());
    return dir.file("robot.yaml");
  }
  std::string expectedFile(const Fault& f) const { return dir.file(std::string(f.file) == "yaml" ? "robot.yaml" : "synthetic.xml"); }
  centaur_test::TempDir dir{"centaur-robot-check"};
};

class BrokenYaml : public BrokenDescription {};
class BrokenModel : public BrokenDescription {};

TEST_P(BrokenYaml, ReaderNamesFileAndKey) {
  const Fault& f = GetParam();
  const std::string path = write(f);
  try {
    centaur::robot::readRobotDescription(path);
    FAIL() << f.what << ": accepted";
  } catch (const centaur::InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(expectedFile(f)), std::string::npos) << m;
    if (*f.key) {
      EXPECT_NE(m.find(std::string("key '") + f.key + "'"), std::string::npos) << m;
    }
    EXPECT_NE(m.find(f.message), std::string::npos) << m;
  }
}

TEST_P(BrokenModel, CheckListsTheProblemAndDerivesNothing) {
  const Fault& f = GetParam();
  const auto d = centaur::robot::readRobotDescription(write(f));
  const auto r = centaur::robot::checkRobot(d);
  EXPECT_FALSE(r.facts.has_value()) << f.what;
  bool found = false;
  std::string all;
  for (const auto& p : r.problems) {
    all += p.text() + "\n";
    found = found || (p.file == expectedFile(f) && p.key == f.key && p.message.find(f.message) != std::string::npos);
  }
  EXPECT_TRUE(found) << f.what << ":\n" << all;
  EXPECT_THROW(centaur::robot::robotFacts(d), centaur::InputError);
}

std::string faultName(const ::testing::TestParamInfo<Fault>& info) {
  std::string n = info.param.what;
  for (char& c : n) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return n;
}

INSTANTIATE_TEST_SUITE_P(Robot, BrokenYaml, ::testing::ValuesIn(kYamlFaults), faultName);
INSTANTIATE_TEST_SUITE_P(Robot, BrokenModel, ::testing::ValuesIn(kModelFaults), faultName);

TEST(RobotCheck, EveryProblemIsListedNotOnlyTheFirst) {
  centaur_test::TempDir dir{"centaur-robot-check"};
  std::string yaml = replaced(syntheticYaml(), "root: fl_hip", "root: fl_hips");
  yaml = replaced(yaml, "centre: rr_centre", "centre: rr_center");
  centaur_test::writeText(dir.file("synthetic.xml"), syntheticMjcf("position"));
  centaur_test::writeText(dir.file("robot.yaml"), yaml);
  const auto r = centaur::robot::checkRobot(centaur::robot::readRobotDescription(dir.path().string()));
  // two names, and eight position servos
  EXPECT_EQ(r.problems.size(), 10u);
}

}  // namespace
