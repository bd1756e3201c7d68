// ctest-labels: sim physics
// The simulator's perturbations (robot.mass_scale, robot.com_offset, push.*) on the tiny test robot
// (tests/testdata/sim_test_robot.xml, 14 kg): the defaults leave the loaded model untouched; the mass scale scales
// the robot's total mass and its weight on the ground; the CoM offset moves the whole robot's CoM by exactly the
// offset; a push in free fall changes the robot's momentum by exactly the impulse, within its time window only;
// bad values are InputError naming the key.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "common/error.hpp"
#include "sim/mujoco_robot.hpp"
#include "sim/sim_config.hpp"

using namespace centaur;
using namespace centaur::sim;

namespace {

const std::string kModel = std::string(CENTAUR_SOURCE_DIR) + "/tests/testdata/sim_test_robot.xml";
constexpr double kRobotMass = 14.0;

SimSettings settings() {
  SimSettings s;
  s.model_path = kModel;
  return s;
}

int body(const MujocoRobot& r, const char* name) { return mj_name2id(r.model(), mjOBJ_BODY, name); }

/// Holds the arms still with a stiff PD (internal forces only).
class Hold : public Controller {
 public:
  void start(const RobotState& s, JointCommand& c) override {
    c.resize(s.q.size());
    tick(s, c);
  }
  void tick(const RobotState& s, JointCommand& c) noexcept override {
    c.q_ref = s.q * 0.0;
    c.qd_ref.setZero();
    c.tau_ff.setZero();
    c.kp.setConstant(50.0);
    c.kd.setConstant(2.0);
  }
};

/// Total linear momentum of the robot (its subtree) [N s], at the current state (after a step MuJoCo's velocity
/// quantities are those of the step's start: recompute them).
Eigen::Vector3d momentum(const MujocoRobot& r) {
  mj_forward(r.model(), r.data());
  mj_subtreeVel(r.model(), r.data());
  const int root = body(r, "pelvis");
  const mjtNum* v = r.data()->subtree_linvel + 3 * root;
  return r.model()->body_subtreemass[root] * Eigen::Vector3d(v[0], v[1], v[2]);
}

}  // namespace

TEST(Perturbations, DefaultsLeaveTheModelAsLoaded) {
  const SimConfig c = loadSimConfig("", "", {"model=" + kModel});
  EXPECT_EQ(c.robot.mass_scale, 1.0);
  EXPECT_TRUE(c.robot.com_offset.isZero(0.0));
  EXPECT_EQ(c.robot.push.impulse, 0.0);
  MujocoRobot a(settings());
  SimSettings s = settings();
  s.push.impulse = 0.0;
  MujocoRobot b(s);
  for (int i = 0; i < a.model()->nbody; ++i) {
    EXPECT_EQ(a.model()->body_mass[i], b.model()->body_mass[i]);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(a.model()->body_ipos[3 * i + k], b.model()->body_ipos[3 * i + k]);
  }
  EXPECT_NEAR(a.model()->body_subtreemass[body(a, "pelvis")], kRobotMass, 1e-12);
}

TEST(Perturbations, MassScaleScalesTheRobotNotTheWorld) {
  SimSettings s = settings();
  s.mass_scale = 1.1;
  MujocoRobot r(s);
  MujocoRobot nominal(settings());
  EXPECT_NEAR(r.model()->body_subtreemass[body(r, "pelvis")], 1.1 * kRobotMass, 1e-12);
  const int wall = body(r, "wall");
  EXPECT_EQ(r.model()->body_mass[wall], nominal.model()->body_mass[wall]);
  const int pelvis = body(r, "pelvis");
  for (int k = 0; k < 3; ++k) {
    EXPECT_DOUBLE_EQ(r.model()->body_inertia[3 * pelvis + k], 1.1 * nominal.model()->body_inertia[3 * pelvis + k]);
  }
  // At rest on its four wheels the ground carries the scaled weight.
  Hold hold;
  RobotState st;
  st.resize(r.numJoints());
  JointCommand cmd;
  r.read(st);
  hold.start(st, cmd);
  for (int k = 0; k < 1500; ++k) r.controlPeriod(hold, st, cmd);
  Eigen::Matrix3Xd f(3, r.numContactBodies());
  r.contactForces(f);
  EXPECT_NEAR(f.row(2).sum(), 1.1 * kRobotMass * 9.81, 0.02 * kRobotMass * 9.81);
}

TEST(Perturbations, ComOffsetMovesTheWholeRobotsCom) {
  const Eigen::Vector3d offset(0.02, -0.01, 0.015);
  SimSettings s = settings();
  s.com_offset = offset;
  MujocoRobot r(s);
  MujocoRobot nominal(settings());
  const int root = body(r, "pelvis");
  // After reset (mj_forward at the home keyframe: pelvis level) the subtree CoM is the nominal one + offset.
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(r.data()->subtree_com[3 * root + k], nominal.data()->subtree_com[3 * root + k] + offset[k], 1e-12);
  }
  EXPECT_NEAR(r.model()->body_subtreemass[root], kRobotMass, 1e-12);  // the mass is unchanged
  // The shapes stay where they were on the body: the pelvis box and the IMU site did not move with the CoM.
  const int box = mj_name2id(r.model(), mjOBJ_GEOM, "pelvis_box"), imu = mj_name2id(r.model(), mjOBJ_SITE, "imu");
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(r.data()->geom_xpos[3 * box + k], nominal.data()->geom_xpos[3 * box + k], 1e-12);
    EXPECT_NEAR(r.data()->site_xpos[3 * imu + k], nominal.data()->site_xpos[3 * imu + k], 1e-12);
  }
}

TEST(Perturbations, PushGivesExactlyItsImpulseInItsWindow) {
  SimSettings s = settings();
  s.push.impulse = 3.0;  // N s
  s.push.body = "pelvis";
  s.push.direction = Eigen::Vector3d(1.0, 2.0, 0.0);  // normalised by the robot
  s.push.start = 0.05;
  s.push.duration = 0.02;
  MujocoRobot r(s);
  r.data()->qpos[2] += 2.0;  // lift it into free fall: no contact, gravity only along -z
  mj_forward(r.model(), r.data());
  Hold hold;
  RobotState st;
  st.resize(r.numJoints());
  JointCommand cmd;
  r.read(st);
  hold.start(st, cmd);
  const Eigen::Vector3d p0 = momentum(r);
  // Tolerance: the Euler step does not conserve momentum exactly while the arms move (~1e-3 N s here); one
  // physics step of push more or less would be 0.075 N s.
  const double tol = 5e-3;
  for (int k = 0; k < 40; ++k) r.controlPeriod(hold, st, cmd);  // to t = 0.04: before the window
  EXPECT_NEAR((momentum(r) - p0).head<2>().norm(), 0.0, tol);
  for (int k = 0; k < 60; ++k) r.controlPeriod(hold, st, cmd);  // to t = 0.1: after the window
  const Eigen::Vector3d dp = momentum(r) - p0;
  const Eigen::Vector3d expected = 3.0 * Eigen::Vector3d(1.0, 2.0, 0.0).normalized();
  EXPECT_NEAR(dp.x(), expected.x(), tol);
  EXPECT_NEAR(dp.y(), expected.y(), tol);
  EXPECT_NEAR(dp.z(), -kRobotMass * 9.81 * 0.1, tol);  // gravity alone
  const Eigen::Vector3d after = momentum(r);
  for (int k = 0; k < 20; ++k) r.controlPeriod(hold, st, cmd);
  EXPECT_NEAR((momentum(r) - after).head<2>().norm(), 0.0, tol);  // no force after the window
}

TEST(Perturbations, BadValuesNameTheKey) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"robot.mass_scale=3", "robot.mass_scale"},      {"robot.com_offset=[0.5, 0, 0]", "robot.com_offset"},
      {"robot.com_offset=[0, 0]", "robot.com_offset"}, {"push.impulse=-1", "push.impulse"},
      {"push.direction=[0, 0, 0]", "push.direction"},  {"push.duration=0", "push.duration"},
      {"push.colour=red", "push.colour"}};
  for (const auto& [set, key] : cases) {
    try {
      loadSimConfig("", "", {set});
      ADD_FAILURE() << set << " accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  }
  SimSettings s = settings();
  s.push.impulse = 1.0;
  s.push.body = "no_such_body";
  try {
    MujocoRobot r(s);
    ADD_FAILURE() << "unknown push body accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("push.body"), std::string::npos) << e.what();
  }
}
