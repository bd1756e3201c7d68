// ctest-labels: unit
// `centaur model import`: the CENTAURO URDF becomes a loadable MJCF (free joint first, its 39 hinges with one
// motor each at the URDF efforts, 93.11 kg, IMU sensors, feet FL FR RL RR on the ground at home) and a robot.yaml
// with the four feet; a synthetic quadruped without a floating joint gets a free joint, motors from its efforts,
// the missing-effort warning and the same bytes on every import; bad input is an InputError naming the file and
// writes nothing.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>
#include <tinyxml2.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "robot/urdf_import.hpp"
#include "support/temp_dir.hpp"

namespace {

using centaur::robot::importUrdf;
using centaur::robot::UrdfImportReport;

const std::string kCentauro = std::string(CENTAUR_SOURCE_DIR) + "/../shared/reference/centauro/centauro.urdf";

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
  void operator()(mjData* d) const { mj_deleteData(d); }
};
using ModelPtr = std::unique_ptr<mjModel, ModelDeleter>;
using DataPtr = std::unique_ptr<mjData, ModelDeleter>;

ModelPtr load(const std::string& path) {
  char err[1000] = "";
  ModelPtr m(mj_loadXML(path.c_str(), nullptr, err, sizeof err));
  EXPECT_TRUE(m) << path << ": " << err;
  return m;
}

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void writeFile(const std::string& path, const std::string& text) {
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

// Efforts of the URDF's revolute and continuous joints, by name.
std::map<std::string, double> urdfEfforts(const std::string& path) {
  tinyxml2::XMLDocument doc;
  EXPECT_EQ(doc.LoadFile(path.c_str()), tinyxml2::XML_SUCCESS);
  std::map<std::string, double> out;
  for (auto* j = doc.RootElement()->FirstChildElement("joint"); j; j = j->NextSiblingElement("joint")) {
    const std::string type = j->Attribute("type");
    if (type != "revolute" && type != "continuous") continue;
    double effort = 0.0;
    if (auto* limit = j->FirstChildElement("limit")) limit->QueryDoubleAttribute("effort", &effort);
    out[j->Attribute("name")] = effort;
  }
  return out;
}

int countContaining(const std::vector<std::string>& lines, const std::string& part) {
  return static_cast<int>(std::count_if(lines.begin(), lines.end(), [&](const std::string& l) { return l.find(part) != std::string::npos; }));
}

// Each motor drives the hinge of its name with ctrlrange = -+ the expected effort.
void expectMotors(const mjModel* m, const std::map<std::string, double>& efforts) {
  ASSERT_EQ(m->nu, static_cast<int>(efforts.size()));
  for (int a = 0; a < m->nu; ++a) {
    const std::string joint = mj_id2name(m, mjOBJ_JOINT, m->actuator_trnid[2 * a]);
    EXPECT_EQ(mj_id2name(m, mjOBJ_ACTUATOR, a), joint);
    ASSERT_TRUE(efforts.count(joint)) << joint;
    EXPECT_TRUE(m->actuator_ctrllimited[a]) << joint;
    EXPECT_EQ(m->actuator_ctrlrange[2 * a], -efforts.at(joint)) << joint;
    EXPECT_EQ(m->actuator_ctrlrange[2 * a + 1], efforts.at(joint)) << joint;
    EXPECT_EQ(m->actuator_gear[6 * a], 1.0);
  }
}

// The three IMU sensors on site `imu`.
void expectImu(const mjModel* m) {
  const int site = mj_name2id(m, mjOBJ_SITE, "imu");
  ASSERT_GE(site, 0);
  const std::pair<const char*, int> sensors[] = {{"imu_quat", mjSENS_FRAMEQUAT}, {"imu_gyro", mjSENS_GYRO}, {"imu_acc", mjSENS_ACCELEROMETER}};
  for (const auto& [name, type] : sensors) {
    const int s = mj_name2id(m, mjOBJ_SENSOR, name);
    ASSERT_GE(s, 0) << name;
    EXPECT_EQ(m->sensor_type[s], type) << name;
    EXPECT_EQ(m->sensor_objtype[s], mjOBJ_SITE) << name;
    EXPECT_EQ(m->sensor_objid[s], site) << name;
  }
}

// robot.yaml's feet FL FR RL RR name centre sites on the right side of the base at the home keyframe (front x > 0,
// left y > 0), with the lowest contact point (centre minus `radius`) on the ground.
void expectFeet(const mjModel* m, const std::string& yaml_path, double radius) {
  const YAML::Node y = YAML::LoadFile(yaml_path);
  ASSERT_TRUE(y["feet"].IsMap());
  EXPECT_EQ(y["feet"].size(), 4u);
  const int key = mj_name2id(m, mjOBJ_KEY, y["home"].as<std::string>().c_str());
  ASSERT_GE(key, 0);
  DataPtr d(mj_makeData(m));
  mj_resetDataKeyframe(m, d.get(), key);
  mj_kinematics(m, d.get());
  const char* names[] = {"FL", "FR", "RL", "RR"};
  const double sx[] = {1, 1, -1, -1}, sy[] = {1, -1, 1, -1};
  double lowest = 1e9;
  for (int k = 0; k < 4; ++k) {
    ASSERT_TRUE(y["feet"][names[k]].IsMap()) << names[k];
    const std::string centre = y["feet"][names[k]]["centre"].as<std::string>();
    const int s = mj_name2id(m, mjOBJ_SITE, centre.c_str());
    ASSERT_GE(s, 0) << centre;
    const double* p = d->site_xpos + 3 * s;
    EXPECT_GT(sx[k] * (p[0] - d->qpos[0]), 0.0) << names[k];
    EXPECT_GT(sy[k] * (p[1] - d->qpos[1]), 0.0) << names[k];
    lowest = std::min(lowest, p[2] - radius);
  }
  EXPECT_NEAR(lowest, 0.0, 1e-6);
}

TEST(UrdfImport, CentauroBecomesAComplete39DofModel) {
  if (!std::filesystem::exists(kCentauro)) GTEST_SKIP() << "the reference URDF is absent: " << kCentauro;
  centaur_test::TempDir dir;
  const UrdfImportReport r = importUrdf(kCentauro, dir.file("out"));
  EXPECT_EQ(r.name, "centauro");
  EXPECT_EQ(r.mjcf_path, dir.file("out") + "/centauro.xml");
  EXPECT_EQ(r.yaml_path, dir.file("out") + "/robot.yaml");
  EXPECT_EQ(r.hinge_joints, 39);
  EXPECT_NEAR(r.total_mass, 93.11, 93.11e-3);
  // 80 meshes: the file has 88 <mesh> lines, 8 of them inside XML comments.
  EXPECT_EQ(countContaining(r.warnings, "not found, dropped"), 80);
  EXPECT_EQ(countContaining(r.warnings, "link 'pelvis': mesh 'package://centauro_urdf/meshes/pelvis.stl' not found, dropped"), 1);

  ModelPtr m = load(r.mjcf_path);
  ASSERT_TRUE(m);
  ASSERT_GT(m->njnt, 0);
  EXPECT_EQ(m->jnt_type[0], mjJNT_FREE);
  EXPECT_EQ(m->jnt_qposadr[0], 0);
  EXPECT_EQ(m->nq, 7 + 39);
  EXPECT_NEAR(mj_getTotalmass(m.get()), 93.11, 93.11e-3);
  const std::map<std::string, double> efforts = urdfEfforts(kCentauro);
  std::set<std::string> hinges, expected;
  for (int j = 0; j < m->njnt; ++j) {
    if (m->jnt_type[j] == mjJNT_HINGE) hinges.insert(mj_id2name(m.get(), mjOBJ_JOINT, j));
    else EXPECT_EQ(j, 0) << "a second non-hinge joint";
  }
  for (const auto& [name, effort] : efforts) expected.insert(name);
  EXPECT_EQ(hinges.size(), 39u);
  EXPECT_EQ(hinges, expected);
  expectMotors(m.get(), efforts);
  expectImu(m.get());
  ASSERT_EQ(m->nuser_jnt, 1);  // velocity limits where RobotModel reads qd_max
  EXPECT_EQ(m->jnt_user[mj_name2id(m.get(), mjOBJ_JOINT, "j_wheel_1")], 20.0);
  EXPECT_EQ(m->opt.timestep, 0.0005);
  EXPECT_EQ(m->opt.integrator, mjINT_EULER);
  expectFeet(m.get(), r.yaml_path, 0.078);  // the wheel cylinders' radius

  const YAML::Node y = YAML::LoadFile(r.yaml_path);
  EXPECT_EQ(y["name"].as<std::string>(), "centauro");
  EXPECT_EQ(y["base"].as<std::string>(), "pelvis");
  EXPECT_EQ(y["feet"]["FL"]["contact"].as<std::string>(), "wheel_1");
  EXPECT_EQ(y["feet"]["RR"]["wheel_joint"].as<std::string>(), "j_wheel_4");
  EXPECT_EQ(y["feet"]["RR"]["type"].as<std::string>(), "wheel");
  ASSERT_EQ(y["upper_body"]["arms"].size(), 2u);
  EXPECT_EQ(y["upper_body"]["arms"][1]["mirrors"].as<std::string>(), "left");
  EXPECT_EQ(y["upper_body"]["torso_joints"][0].as<std::string>(), "torso_yaw");
}

// A box base with four two-link legs (sphere feet), no floating joint; the rear-right hip is continuous, the
// front-right knee has no effort limit; one mesh exists (package://), one does not.
std::string quadrupedUrdf() {
  auto inertial = [](double mass) {
    const std::string i = std::to_string(mass * 0.01);
    return "<inertial><mass value=\"" + std::to_string(mass) + "\"/><inertia ixx=\"" + i + "\" ixy=\"0\" ixz=\"0\" iyy=\"" + i +
           "\" iyz=\"0\" izz=\"" + i + "\"/></inertial>";
  };
  std::string u = "<?xml version=\"1.0\"?>\n<robot name=\"Test Bot\">\n  <link name=\"base\">" + inertial(10.0) +
                  "<visual><geometry><box size=\"0.6 0.3 0.1\"/></geometry></visual>"
                  "<visual><geometry><mesh filename=\"package://bot/meshes/tet.stl\"/></geometry></visual>"
                  "<collision><geometry><mesh filename=\"../meshes/missing.stl\"/></geometry></collision></link>\n"
                  "  <link name=\"imu_link\"/>\n  <joint name=\"imu_fixed\" type=\"fixed\"><parent link=\"base\"/>"
                  "<child link=\"imu_link\"/><origin xyz=\"0.1 0 0.05\"/></joint>\n";
  const char* legs[] = {"fl", "fr", "rl", "rr"};
  const double x[] = {0.25, 0.25, -0.25, -0.25}, y[] = {0.15, -0.15, 0.15, -0.15};
  for (int k = 0; k < 4; ++k) {
    const std::string l = legs[k];
    const std::string hip_type = l == "rr" ? "continuous" : "revolute";
    const std::string hip_limit = l == "rr" ? "<limit effort=\"40\" velocity=\"10\"/>"
                                            : "<limit lower=\"-1\" upper=\"1\" effort=\"40\" velocity=\"10\"/>";
    const std::string knee_limit = l == "fr" ? "<limit lower=\"-2\" upper=\"0\" velocity=\"12\"/>"
                                             : "<limit lower=\"-2\" upper=\"0\" effort=\"30\" velocity=\"12\"/>";
    u += "  <link name=\"" + l + "_thigh\">" + inertial(1.0) + "</link>\n";
    u += "  <link name=\"" + l + "_shank\">" + inertial(0.5) +
         "<collision><origin xyz=\"0 0 -0.2\"/><geometry><sphere radius=\"0.02\"/></geometry></collision></link>\n";
    u += "  <joint name=\"" + l + "_hip\" type=\"" + hip_type + "\"><parent link=\"base\"/><child link=\"" + l +
         "_thigh\"/><origin xyz=\"" + std::to_string(x[k]) + " " + std::to_string(y[k]) + " 0\"/><axis xyz=\"0 1 0\"/>" +
         hip_limit + "</joint>\n";
    u += "  <joint name=\"" + l + "_knee\" type=\"revolute\"><parent link=\"" + l + "_thigh\"/><child link=\"" + l +
         "_shank\"/><origin xyz=\"0 0 -0.2\"/><axis xyz=\"0 1 0\"/>" + knee_limit + "</joint>\n";
  }
  return u + "</robot>\n";
}

// A tetrahedron as binary STL, faces outward.
std::string tetrahedronStl() {
  const float v[4][3] = {{0, 0, 0}, {0.1f, 0, 0}, {0, 0.1f, 0}, {0, 0, 0.1f}};
  const int faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  std::string s(80, '\0');
  const std::uint32_t n = 4;
  s.append(reinterpret_cast<const char*>(&n), 4);
  for (const auto& f : faces) {
    const float normal[3] = {0, 0, 0};
    s.append(reinterpret_cast<const char*>(normal), 12);
    for (int i : f) s.append(reinterpret_cast<const char*>(v[i]), 12);
    s.append(2, '\0');
  }
  return s;
}

TEST(UrdfImport, QuadrupedGetsFreeJointMotorsAndTheSameBytesTwice) {
  centaur_test::TempDir dir;
  const std::string urdf = dir.file("bot/urdf/bot.urdf");
  writeFile(urdf, quadrupedUrdf());
  writeFile(dir.file("bot/meshes/tet.stl"), tetrahedronStl());
  const UrdfImportReport r = importUrdf(urdf, dir.file("a"));
  EXPECT_EQ(r.name, "test_bot");
  EXPECT_EQ(r.hinge_joints, 8);
  EXPECT_NEAR(r.total_mass, 16.0, 1e-9);
  EXPECT_EQ(countContaining(r.warnings, "joint 'fr_knee': no effort limit in the URDF, motor limited to 1 N m: set it"), 1);
  EXPECT_EQ(countContaining(r.warnings, "link 'base': mesh '../meshes/missing.stl' not found, dropped"), 1);
  EXPECT_EQ(countContaining(r.warnings, "not found, dropped"), 1);
  EXPECT_EQ(countContaining(r.warnings, "joint 'rr_hip' is continuous but no wheel"), 1);

  ModelPtr m = load(r.mjcf_path);
  ASSERT_TRUE(m);
  EXPECT_EQ(m->jnt_type[0], mjJNT_FREE);
  EXPECT_EQ(m->jnt_qposadr[0], 0);
  EXPECT_STREQ(mj_id2name(m.get(), mjOBJ_JOINT, 0), "root");
  EXPECT_STREQ(mj_id2name(m.get(), mjOBJ_BODY, m->jnt_bodyid[0]), "base");
  EXPECT_EQ(m->nmesh, 1);  // the mesh found through package:// is kept
  std::map<std::string, double> efforts;
  for (const char* l : {"fl", "fr", "rl", "rr"}) {
    efforts[std::string(l) + "_hip"] = 40.0;
    efforts[std::string(l) + "_knee"] = 30.0;
  }
  efforts["fr_knee"] = 1.0;
  expectMotors(m.get(), efforts);
  expectImu(m.get());
  EXPECT_EQ(m->site_bodyid[mj_name2id(m.get(), mjOBJ_SITE, "imu")], mj_name2id(m.get(), mjOBJ_BODY, "imu_link"));
  expectFeet(m.get(), r.yaml_path, 0.02);  // the spheres' radius
  const YAML::Node y = YAML::LoadFile(r.yaml_path);
  EXPECT_EQ(y["name"].as<std::string>(), "test_bot");
  EXPECT_EQ(y["feet"]["FR"]["root"].as<std::string>(), "fr_thigh");
  EXPECT_EQ(y["feet"]["FR"]["type"].as<std::string>(), "point");
  EXPECT_EQ(y["feet"]["RR"]["type"].as<std::string>(), "point");  // the continuous joint is not the contact body's

  const UrdfImportReport again = importUrdf(urdf, dir.file("b"));
  EXPECT_EQ(readFile(again.mjcf_path), readFile(r.mjcf_path));
  EXPECT_EQ(readFile(again.yaml_path), readFile(r.yaml_path));
  EXPECT_EQ(again.warnings, r.warnings);
}

// `urdf` written to a fresh folder and imported into an existing empty folder: InputError naming the file, and
// neither that folder nor /tmp gains a file.
void expectRefused(const std::string& urdf_text, const std::string& message_part) {
  centaur_test::TempDir dir;
  const std::string urdf = dir.file("in/robot.urdf");
  if (!urdf_text.empty()) writeFile(urdf, urdf_text);
  std::filesystem::create_directories(dir.file("out"));
  try {
    importUrdf(urdf, dir.file("out"));
    ADD_FAILURE() << "no InputError for " << message_part;
  } catch (const centaur::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(urdf), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(message_part), std::string::npos) << e.what();
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir.file("out")));
  EXPECT_THROW(importUrdf(urdf, dir.file("new")), centaur::InputError);
  EXPECT_FALSE(std::filesystem::exists(dir.file("new")));
  const std::string temporaries = "centaur-urdf-import." + std::to_string(::getpid()) + ".";
  for (const auto& e : std::filesystem::directory_iterator(std::filesystem::temp_directory_path())) {
    EXPECT_NE(e.path().filename().string().rfind(temporaries, 0), 0u) << e.path();
  }
}

TEST(UrdfImport, BadInputIsAnInputErrorNamingTheFileAndWritesNothing) {
  expectRefused("", "robot.urdf");  // missing
  expectRefused("<mujoco><worldbody/></mujoco>\n", "not a URDF");
  expectRefused("this is not XML <", "not a URDF");
  expectRefused("<robot name=\"r\"/>\n", "no <link>");
  std::string prismatic = quadrupedUrdf();
  const std::string knee = "name=\"fl_knee\" type=\"revolute\"";
  prismatic.replace(prismatic.find(knee), knee.size(), "name=\"fl_knee\" type=\"prismatic\"");
  expectRefused(prismatic, "joint 'fl_knee' is of type 'prismatic'");
  // A moving link without mass: MuJoCo's compiler refuses it.
  std::string massless = quadrupedUrdf();
  const std::string shank = "<link name=\"rl_shank\">";
  const std::size_t at = massless.find(shank);
  massless.replace(at, massless.find("</link>", at) + 7 - at, "<link name=\"rl_shank\"/>");
  expectRefused(massless, "MuJoCo");
}

TEST(UrdfImport, RobotNamesAreSanitized) {
  EXPECT_EQ(centaur::robot::sanitizeRobotName("Test Bot"), "test_bot");
  EXPECT_EQ(centaur::robot::sanitizeRobotName("a.b/C-d_9"), "a_b_c-d_9");
  EXPECT_EQ(centaur::robot::sanitizeRobotName(""), "robot");
  EXPECT_EQ(centaur::robot::sanitizeRobotName(std::string(100, 'x')).size(), 64u);
}

}  // namespace
