// ctest-labels: unit
// The report's robot: forward kinematics from a base pose and logged joints puts CENTAURO's wheel centres where
// the model facts say (docs/model.md) for any base pose; the scene holds every geom of the MJCF once, meshes
// included; a log joint the model lacks is an InputError naming the file and key.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <Eigen/Geometry>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "model/chain_from_mjcf.hpp"
#include "report/channel_codec.hpp"
#include "report/kinematic_model.hpp"
#include "report/scene_geometry.hpp"

namespace report = centaur::report;

namespace {

/// Actuated joint names (actuator order, as logs store them) and their values in keyframe `home`.
void homeJoints(const report::KinematicModel& km, std::vector<std::string>& names, std::vector<double>& q) {
  const mjModel* m = km.model();
  const int key = mj_name2id(m, mjOBJ_KEY, "home");
  ASSERT_GE(key, 0);
  for (int a = 0; a < m->nu; ++a) {
    const int j = m->actuator_trnid[2 * a];
    names.emplace_back(mj_id2name(m, mjOBJ_JOINT, j));
    q.push_back(m->key_qpos[key * m->nq + m->jnt_qposadr[j]]);
  }
}

}  // namespace

TEST(ReportKinematics, WheelCentresOfTheHomePostureFollowAnyBasePose) {
  report::KinematicModel km(centaur::model::centauroMjcfPath());
  std::vector<std::string> names;
  std::vector<double> q;
  homeJoints(km, names, q);
  ASSERT_EQ(names.size(), 39u);
  const std::vector<int> addresses = km.jointAddresses(names, "log.h5", "joint_names");
  const Eigen::Vector3d p(1.0, 2.0, 0.8);
  const Eigen::Quaterniond yaw(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
  const Eigen::Quaterniond pitch = yaw * Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY()));
  for (const Eigen::Quaterniond& r : {yaw, pitch}) {
    const double wxyz[4] = {r.w(), r.x(), r.y(), r.z()};
    std::vector<double> poses;
    km.bodyPoses(p.data(), wxyz, q.data(), addresses, poses);
    ASSERT_EQ(poses.size(), 7 * km.movingBodies().size());
    EXPECT_EQ(km.bodyName(km.movingBodies()[0]), "pelvis");
    EXPECT_NEAR((Eigen::Vector3d(poses[0], poses[1], poses[2]) - p).norm(), 0.0, 1e-12);
    EXPECT_NEAR(std::abs(poses[3] * r.w() + poses[4] * r.x() + poses[5] * r.y() + poses[6] * r.z()), 1.0, 1e-12);
    // docs/model.md: home wheel centres in the pelvis frame (+-0.35, +-0.35, -0.64085), FL FR RL RR = wheel_1..4
    const double sx[4] = {1, 1, -1, -1}, sy[4] = {1, -1, 1, -1};
    for (int k = 0; k < 4; ++k) {
      const int body = km.bodyId("wheel_" + std::to_string(k + 1));
      const auto it = std::find(km.movingBodies().begin(), km.movingBodies().end(), body);
      ASSERT_NE(it, km.movingBodies().end());
      const std::size_t slot = static_cast<std::size_t>(it - km.movingBodies().begin());
      const Eigen::Vector3d w(poses[7 * slot], poses[7 * slot + 1], poses[7 * slot + 2]);
      const Eigen::Vector3d expect = p + r * Eigen::Vector3d(0.35 * sx[k], 0.35 * sy[k], -0.64085);
      EXPECT_LT((w - expect).norm(), 1e-4) << "wheel_" << k + 1;
      EXPECT_NEAR(km.contactRadius(body), 0.078, 1e-12);
    }
  }
}

TEST(ReportKinematics, EffortLimitsAreTheActuatorRangesAndUnknownJointsAreRefused) {
  report::KinematicModel km(centaur::model::centauroMjcfPath());
  const mjModel* m = km.model();
  std::vector<std::string> names;
  std::vector<double> q;
  homeJoints(km, names, q);
  const std::vector<double> limits = km.effortLimits(names);
  for (int a = 0; a < m->nu; ++a) EXPECT_EQ(limits[a], m->actuator_ctrlrange[2 * a + 1]) << names[a];
  EXPECT_TRUE(std::isinf(km.effortLimits({"no_such_joint"})[0]));
  try {
    km.jointAddresses({"torso_yaw", "knee_99"}, "run.h5", "joint_names");
    FAIL() << "no InputError";
  } catch (const centaur::InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("run.h5"), std::string::npos) << what;
    EXPECT_NE(what.find("joint_names"), std::string::npos) << what;
    EXPECT_NE(what.find("knee_99"), std::string::npos) << what;
  }
}

TEST(ReportScene, EveryGeomOfCentauroOnceWithItsBodySlot) {
  report::KinematicModel km(centaur::model::centauroMjcfPath());
  const mjModel* m = km.model();
  const nlohmann::json s = report::sceneGeometry(km);
  const std::size_t slots = km.movingBodies().size() + km.staticBodies().size();
  EXPECT_EQ(s["bodies"].size(), slots);
  EXPECT_EQ(s["moving"], km.movingBodies().size());
  EXPECT_EQ(s["geoms"].size(), static_cast<std::size_t>(m->ngeom));  // all visible, none a height field
  std::map<std::string, int> types;
  for (const auto& g : s["geoms"]) {
    ++types[g["type"].get<std::string>()];
    EXPECT_LT(g["slot"].get<std::size_t>(), slots);
    EXPECT_EQ(g["quat"].size(), 4u);
  }
  std::map<std::string, int> expect;
  const char* names[] = {"plane", "", "sphere", "capsule", "ellipsoid", "cylinder", "box", "mesh"};
  for (int g = 0; g < m->ngeom; ++g) ++expect[names[m->geom_type[g]]];
  EXPECT_EQ(types, expect);
  EXPECT_GE(types["capsule"], 20);
  EXPECT_GE(types["cylinder"], 30);
  EXPECT_TRUE(s["meshes"].empty());
  // the wall and the ground are static slots
  const auto& bodies = s["bodies"];
  const auto wall = std::find(bodies.begin(), bodies.end(), "wall");
  ASSERT_NE(wall, bodies.end());
  EXPECT_GE(static_cast<std::size_t>(wall - bodies.begin()), km.movingBodies().size());
}

TEST(ReportScene, MeshesAreStoredOnceWithTheirVerticesAndFaces) {
  report::KinematicModel km(std::string(CENTAUR_SOURCE_DIR) + "/tests/testdata/report_mesh_robot.xml");
  const nlohmann::json s = report::sceneGeometry(km);
  EXPECT_EQ(s["moving"], 2);  // base, arm
  ASSERT_EQ(s["meshes"].size(), 1u);
  EXPECT_EQ(report::decodeBase64(s["meshes"][0]["vertices"].get<std::string>()).size(), 4u * 3u * 4u);
  EXPECT_EQ(report::decodeBase64(s["meshes"][0]["faces"].get<std::string>()).size(), 4u * 3u * 4u);
  std::vector<std::string> types;
  for (const auto& g : s["geoms"]) types.push_back(g["type"]);
  for (const char* t : {"mesh", "ellipsoid", "cylinder", "plane", "box"}) {
    EXPECT_NE(std::find(types.begin(), types.end(), t), types.end()) << t;
  }
  for (const auto& g : s["geoms"]) {
    if (g["type"] == "mesh") {
      EXPECT_EQ(g["mesh"], 0);
      EXPECT_NEAR(g["rgba"][0].get<double>(), 0.8, 1e-6);  // from the material
    }
  }
  EXPECT_THROW(report::KinematicModel(std::string(CENTAUR_SOURCE_DIR) + "/tests/testdata/no_such.xml"),
               centaur::InputError);
}
