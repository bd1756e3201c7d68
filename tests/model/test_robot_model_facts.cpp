// ctest-labels: unit physics
// Model facts of models/centauro/centauro.xml against the reference figures (MODEL.md): mass, joints,
// limits, home-posture and zero-posture wheel centres and CoM in the pelvis frame, MJCF contents.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "model/robot_model.hpp"

using centaur::RobotModel;

namespace {

const std::string kModel = std::string(CENTAUR_SOURCE_DIR) + "/models/centauro/centauro.xml";

const std::vector<std::string> kJoints = {
    "torso_yaw",   "j_arm1_1",    "j_arm1_2",     "j_arm1_3",      "j_arm1_4",    "j_arm1_5",  "j_arm1_6",
    "j_arm1_7",    "j_arm2_1",    "j_arm2_2",     "j_arm2_3",      "j_arm2_4",    "j_arm2_5",  "j_arm2_6",
    "j_arm2_7",    "hip_yaw_1",   "hip_pitch_1",  "knee_pitch_1",  "ankle_pitch_1", "ankle_yaw_1", "j_wheel_1",
    "hip_yaw_2",   "hip_pitch_2", "knee_pitch_2", "ankle_pitch_2", "ankle_yaw_2", "j_wheel_2", "hip_yaw_3",
    "hip_pitch_3", "knee_pitch_3", "ankle_pitch_3", "ankle_yaw_3", "j_wheel_3",   "hip_yaw_4", "hip_pitch_4",
    "knee_pitch_4", "ankle_pitch_4", "ankle_yaw_4", "j_wheel_4"};

// Configuration with the pelvis at w_p, orientation w_q, joints qj.
Eigen::VectorXd config(const RobotModel& model, const Eigen::Vector3d& w_p, const Eigen::Quaterniond& w_q,
                       const Eigen::VectorXd& qj) {
  Eigen::VectorXd q(model.nq());
  q << w_p, w_q.w(), w_q.x(), w_q.y(), w_q.z(), qj;
  return q;
}

// Position of a frame in the pelvis frame.
Eigen::Vector3d inPelvis(const RobotModel& model, const std::string& frame) {
  const Eigen::Isometry3d w_T_p = model.framePose(model.frameId("pelvis"));
  return w_T_p.inverse() * model.framePose(model.frameId(frame)).translation();
}

}  // namespace

TEST(CentauroModel, MassAndJoints) {
  RobotModel model(kModel);
  EXPECT_NEAR(model.totalMass(), 93.113, 0.01);
  ASSERT_EQ(model.numJoints(), 39);
  EXPECT_EQ(model.nq(), 46);
  EXPECT_EQ(model.nv(), 45);
  EXPECT_EQ(model.jointNames(), kJoints);
  EXPECT_EQ(model.jointIndex("knee_pitch_3"), 29);
  EXPECT_EQ(model.jointIndex("no_such_joint"), -1);
  EXPECT_EQ(model.frameId("no_such_frame"), -1);
}

TEST(CentauroModel, LimitsFromUrdf) {
  RobotModel model(kModel);
  const auto& L = model.limits();
  for (int k = 1; k <= 4; ++k) {
    const int w = model.jointIndex("j_wheel_" + std::to_string(k));
    EXPECT_TRUE(std::isinf(L.q_min[w]) && L.q_min[w] < 0);
    EXPECT_TRUE(std::isinf(L.q_max[w]) && L.q_max[w] > 0);
    EXPECT_DOUBLE_EQ(L.tau_max[w], 35.0);
    EXPECT_DOUBLE_EQ(L.qd_max[w], 20.0);
    EXPECT_DOUBLE_EQ(L.tau_max[model.jointIndex("hip_pitch_" + std::to_string(k))], 304.0);
  }
  const int knee1 = model.jointIndex("knee_pitch_1");
  EXPECT_DOUBLE_EQ(L.q_min[knee1], -2.4056);
  EXPECT_DOUBLE_EQ(L.q_max[knee1], 2.3994);
  EXPECT_DOUBLE_EQ(L.qd_max[knee1], 8.8);
  const int a27 = model.jointIndex("j_arm2_7");
  EXPECT_DOUBLE_EQ(L.tau_max[a27], 28.32);
  EXPECT_DOUBLE_EQ(L.q_min[a27], -2.5554);
  EXPECT_DOUBLE_EQ(L.q_max[a27], 2.5686);
  // home posture is inside the limits
  const Eigen::VectorXd home = model.homeJoints();
  for (int i = 0; i < model.numJoints(); ++i) {
    EXPECT_GE(home[i], L.q_min[i]) << model.jointNames()[i];
    EXPECT_LE(home[i], L.q_max[i]) << model.jointNames()[i];
  }
}

TEST(CentauroModel, HomeWheelCentresAndComInPelvisFrame) {
  RobotModel model(kModel);
  const Eigen::VectorXd home = model.homeJoints();
  EXPECT_NEAR(home[model.jointIndex("knee_pitch_1")], -1.55576, 1e-9);
  EXPECT_NEAR(home[model.jointIndex("j_arm1_4")], -2.23604, 1e-9);
  // Any base pose: the pelvis-frame figures must not depend on it.
  const Eigen::Quaterniond rot(Eigen::AngleAxisd(0.3, Eigen::Vector3d(0.2, -0.5, 1.0).normalized()));
  for (const Eigen::Quaterniond& w_q : {Eigen::Quaterniond::Identity(), rot}) {
    model.update(config(model, Eigen::Vector3d(0.4, -1.0, 0.7), w_q, home), Eigen::VectorXd::Zero(model.nv()));
    const double sx[4] = {1, 1, -1, -1}, sy[4] = {1, -1, 1, -1};
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector3d expected(0.35 * sx[k], 0.35 * sy[k], -0.6408);
      const std::string name = "wheel_" + std::to_string(k + 1);
      EXPECT_LT((inPelvis(model, name) - expected).norm(), 1e-3) << name << ": " << inPelvis(model, name).transpose();
      EXPECT_LT((inPelvis(model, "wheel_centre_" + std::to_string(k + 1)) - expected).norm(), 1e-3);
    }
    const Eigen::Isometry3d w_T_p = model.framePose(model.frameId("pelvis"));
    const Eigen::Vector3d p_com = w_T_p.inverse() * model.com();
    EXPECT_LT((p_com - Eigen::Vector3d(0.105, 0.0003, -0.0339)).norm(), 2e-3) << p_com.transpose();
    EXPECT_LT((inPelvis(model, "imu") - Eigen::Vector3d(0.24832, 0, 0.015)).norm(), 1e-4);
    EXPECT_LT((inPelvis(model, "torso_2") - Eigen::Vector3d(0.2, 0, 0.256)).norm(), 1e-4);
    EXPECT_LT((inPelvis(model, "arm1_1") - Eigen::Vector3d(0.2457, 0.1691, 0.3726)).norm(), 1e-3);
    EXPECT_LT((inPelvis(model, "ball1_tip") - Eigen::Vector3d(0.5618, 0.1458, 0.353)).norm(), 1e-3);
    EXPECT_LT((inPelvis(model, "ball2_tip") - Eigen::Vector3d(0.5618, -0.1458, 0.353)).norm(), 1e-3);
    // wheel axes are horizontal (lateral) at home: the wheels roll along the pelvis x axis
    for (int k = 1; k <= 4; ++k) {
      const Eigen::Vector3d axis =
          w_T_p.linear().transpose() * model.framePose(model.frameId("wheel_" + std::to_string(k))).linear().col(2);
      EXPECT_NEAR(std::abs(axis.y()), 1.0, 1e-6);
    }
  }
}

TEST(CentauroModel, ZeroPostureWheelCentresAndCom) {
  RobotModel model(kModel);
  model.update(config(model, Eigen::Vector3d::Zero(), Eigen::Quaterniond::Identity(),
                      Eigen::VectorXd::Zero(model.numJoints())),
               Eigen::VectorXd::Zero(model.nv()));
  const double sx[4] = {1, 1, -1, -1}, sy[4] = {1, -1, 1, -1};
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector3d expected(0.25 * sx[k], 0.222 * sy[k], -0.856);
    EXPECT_LT((inPelvis(model, "wheel_" + std::to_string(k + 1)) - expected).norm(), 1e-3);
  }
  EXPECT_LT((model.com() - Eigen::Vector3d(0.0924, 0.0003, -0.153)).norm(), 2e-3) << model.com().transpose();
}

TEST(CentauroMjcf, ActuatorsSensorsContactsKeyframe) {
  char err[1000] = "";
  mjModel* m = mj_loadXML(kModel.c_str(), nullptr, err, sizeof(err));
  ASSERT_NE(m, nullptr) << err;
  EXPECT_DOUBLE_EQ(m->opt.timestep, 0.0005);
  ASSERT_EQ(m->nu, 39);
  RobotModel model(kModel);
  for (int a = 0; a < m->nu; ++a) {
    const int j = m->actuator_trnid[2 * a];
    const std::string name = mj_id2name(m, mjOBJ_JOINT, j);
    EXPECT_EQ(std::string(mj_id2name(m, mjOBJ_ACTUATOR, a)), name);
    EXPECT_EQ(name, kJoints[a]);
    EXPECT_TRUE(m->actuator_ctrllimited[a]);
    EXPECT_DOUBLE_EQ(m->actuator_ctrlrange[2 * a + 1], model.limits().tau_max[a]);
    EXPECT_DOUBLE_EQ(m->actuator_ctrlrange[2 * a], -model.limits().tau_max[a]);
  }
  for (const char* s : {"imu_quat", "imu_gyro", "imu_acc"}) EXPECT_GE(mj_name2id(m, mjOBJ_SENSOR, s), 0) << s;
  // Only the wheels (and ground / wall) take part in collisions.
  int colliding = 0;
  for (int g = 0; g < m->ngeom; ++g) {
    if (m->geom_contype[g] == 0 && m->geom_conaffinity[g] == 0) continue;
    const std::string name = mj_id2name(m, mjOBJ_GEOM, g) ? mj_id2name(m, mjOBJ_GEOM, g) : "";
    EXPECT_TRUE(name.rfind("wheel_", 0) == 0 || name == "ground" || name == "wall") << name;
    if (name.rfind("wheel_", 0) == 0) {
      EXPECT_EQ(m->geom_type[g], mjGEOM_CYLINDER);
      EXPECT_DOUBLE_EQ(m->geom_size[3 * g], 0.078);
      EXPECT_DOUBLE_EQ(m->geom_size[3 * g + 1], 0.03);
      EXPECT_DOUBLE_EQ(m->geom_friction[3 * g], 1.0);
      ++colliding;
    }
  }
  EXPECT_EQ(colliding, 4);
  // Keyframe home: wheels touch the ground (4 wheels in contact, penetration < 0.1 mm), wall not touched.
  mjData* d = mj_makeData(m);
  mj_resetDataKeyframe(m, d, mj_name2id(m, mjOBJ_KEY, "home"));
  mj_forward(m, d);
  EXPECT_NEAR(d->qpos[2], 0.7188, 1e-3);
  const int wall = mj_name2id(m, mjOBJ_GEOM, "wall");
  const int ground = mj_name2id(m, mjOBJ_GEOM, "ground");
  ASSERT_GE(wall, 0);
  ASSERT_GE(ground, 0);
  bool touched[4] = {false, false, false, false};
  for (int c = 0; c < d->ncon; ++c) {
    EXPECT_NE(d->contact[c].geom1, wall);
    EXPECT_NE(d->contact[c].geom2, wall);
    EXPECT_GT(d->contact[c].dist, -1e-4);
    const int wg = d->contact[c].geom1 == ground ? d->contact[c].geom2 : d->contact[c].geom1;
    const std::string name = mj_id2name(m, mjOBJ_GEOM, wg);
    touched[name.back() - '1'] = true;
  }
  for (int k = 0; k < 4; ++k) EXPECT_TRUE(touched[k]) << "wheel " << k + 1;
  // Moving the wall (body_pos) to the rear wheels makes them collide with it.
  const int wall_body = mj_name2id(m, mjOBJ_BODY, "wall");
  m->body_pos[3 * wall_body] = -0.35 - 0.07;  // rear wheel centres at x = -0.35, radius 0.078
  mj_forward(m, d);
  int wall_contacts = 0;
  for (int c = 0; c < d->ncon; ++c) wall_contacts += (d->contact[c].geom1 == wall || d->contact[c].geom2 == wall);
  EXPECT_GE(wall_contacts, 2);
  mj_deleteData(d);
  mj_deleteModel(m);
}

TEST(CentauroModel, BadFileIsInputError) {
  EXPECT_THROW(RobotModel("/nonexistent/centauro.xml"), centaur::InputError);
}
