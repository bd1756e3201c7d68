// What centaur derives from a robot description: hand-computed values on a small synthetic robot, and on
// CENTAURO the template preset that was lumped by hand from its model (model/template_params.cpp), the arm
// mirror signs the arm-flywheel plan uses and the Raibert stabilizer's directions.
#include <gtest/gtest.h>

#include <cmath>

#include "data/arm_trajectory.hpp"
#include "model/template_params.hpp"
#include "robot/robot_facts.hpp"
#include "robot/robot_registry.hpp"
#include "robot/synthetic_robot.hpp"
#include "support/temp_dir.hpp"

namespace {

using centaur::robot::RobotFacts;

struct Body {
  double m;
  Eigen::Vector3d c, I;  // CoM at home (B), principal inertia = body axes (no rotation in the synthetic model)
};

// Inertia of a set of bodies about their joint CoM: parallel axis, written out.
Eigen::Matrix3d lumped(const std::vector<Body>& bodies, Eigen::Vector3d& com, double& mass) {
  mass = 0.0;
  com.setZero();
  for (const auto& b : bodies) mass += b.m, com += b.m * b.c;
  com /= mass;
  Eigen::Matrix3d I = Eigen::Matrix3d::Zero();
  for (const auto& b : bodies) {
    const Eigen::Vector3d r = b.c - com;
    I += Eigen::Matrix3d(b.I.asDiagonal()) + b.m * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
  }
  return I;
}

std::vector<Body> waistBodies() {
  const Eigen::Vector3d arm(0.01, 0.01, 0.01);
  return {{10.0, {0, 0, 0}, {1, 2, 3}},          {2.0, {0.1, 0, 0.2}, {0.1, 0.2, 0.3}},
          {0.5, {0, 0.3, 0.1}, arm},              {0.5, {0, 0.3, -0.1}, arm},
          {0.5, {0, -0.3, 0.1}, arm},             {0.5, {0, -0.3, -0.1}, arm}};
}

std::vector<Body> allBodies() {
  std::vector<Body> b = waistBodies();
  for (double x : {0.3, -0.3}) {
    for (double y : {0.2, -0.2}) {
      b.push_back({1.0, {x, y, 0.0}, {0.01, 0.01, 0.01}});
      b.push_back({0.5, {x, y, -0.4}, {0.001, 0.001, 0.001}});
    }
  }
  return b;
}

class SyntheticRobot : public ::testing::Test {
 protected:
  void SetUp() override {
    centaur_test::writeText(dir.file("synthetic.xml"), centaur_test::syntheticMjcf());
    centaur_test::writeText(dir.file("robot.yaml"), centaur_test::syntheticYaml());
  }
  centaur_test::TempDir dir{"centaur-robot"};
};

TEST_F(SyntheticRobot, TemplateIsTheLumpedWaistAndLegs) {
  const auto d = centaur::robot::readRobotDescription(dir.path().string());
  const auto r = centaur::robot::checkRobot(d);
  ASSERT_TRUE(r.problems.empty()) << r.problems.front().text();
  const RobotFacts& f = *r.facts;
  Eigen::Vector3d com;
  double mass = 0.0;
  const Eigen::Matrix3d I = lumped(waistBodies(), com, mass);
  const auto& P = f.template_params;
  EXPECT_NEAR(P.waist_mass, 14.0, 1e-12);
  EXPECT_NEAR(mass, 14.0, 1e-12);
  EXPECT_LT((P.waist_com - Eigen::Vector3d(0.2 / 14.0, 0.0, 0.4 / 14.0)).norm(), 1e-12);
  EXPECT_LT((P.waist_inertia - I).norm(), 1e-9) << P.waist_inertia << "\n" << I;
  EXPECT_NEAR(P.foot_mass, 1.5, 1e-12);
  EXPECT_NEAR(f.total_mass, 20.0, 1e-12);
  EXPECT_NEAR(f.home_base_height, 0.45, 1e-12);
  EXPECT_NEAR(P.gravity, 9.81, 1e-12);
  const double sx[4] = {0.3, 0.3, -0.3, -0.3}, sy[4] = {0.2, -0.2, 0.2, -0.2};
  for (int k = 0; k < 4; ++k) {
    EXPECT_LT((P.hip[k] - Eigen::Vector3d(sx[k], sy[k], 0.0)).norm(), 1e-12) << k;
    EXPECT_LT((f.b_p_foot[k] - Eigen::Vector3d(sx[k], sy[k], -0.4)).norm(), 1e-12) << k;
    EXPECT_NEAR(f.foot_radius[k], 0.05, 1e-12);
    EXPECT_NEAR(f.leg_mass[k], 1.5, 1e-12);
  }
}

TEST_F(SyntheticRobot, ArmsMirrorAndPitchAuthorityIsTheCentroidalMomentum) {
  const RobotFacts f = centaur::robot::robotFacts(centaur::robot::readRobotDescription(dir.path().string()));
  ASSERT_EQ(f.arms.size(), 2u);
  EXPECT_TRUE(f.arms[0].mirror_signs.empty());
  ASSERT_EQ(f.arms[1].mirror_signs.size(), 2u);
  EXPECT_EQ(f.arms[1].mirror_signs[0], 1.0);   // both pitch about +y: the same angle mirrors
  EXPECT_EQ(f.arms[1].mirror_signs[1], -1.0);  // both roll about +x: the mirror image turns the other way
  // Shoulder pitch at home: the link's own rotation (Iyy 0.01) plus the lower link (0.01 and 0.5 kg moving at
  // 0.2 m/s along -x, 0.08 m below the robot's CoM at z = -0.02): 0.01 + 0.01 + 0.5 * 0.08 * 0.2.
  EXPECT_NEAR(f.arms[0].pitch_authority[0], 0.028, 1e-12);
  EXPECT_NEAR(f.arms[1].pitch_authority[0], 0.028, 1e-12);
  EXPECT_NEAR(f.arms[0].pitch_authority[1], 0.0, 1e-12);  // a roll joint at home: no pitch momentum
  Eigen::Vector3d com;
  double mass = 0.0;
  const Eigen::Matrix3d I = lumped(allBodies(), com, mass);
  EXPECT_NEAR(com.z(), -0.02, 1e-12);
  EXPECT_NEAR(f.pitch_inertia, I(1, 1), 1e-9);
  EXPECT_NEAR(f.arms[0].pitch_ratio[0], 0.028 / I(1, 1), 1e-9);
  EXPECT_EQ(f.raibert_directions, (std::vector<double>{1.0, 1.0}));
}

TEST_F(SyntheticRobot, LimitsComeFromTheModelUnlessOverridden) {
  const RobotFacts f = centaur::robot::robotFacts(centaur::robot::readRobotDescription(dir.path().string()));
  const auto at = [&](const std::string& j) {
    return static_cast<int>(std::find(f.joint_names.begin(), f.joint_names.end(), j) - f.joint_names.begin());
  };
  ASSERT_EQ(f.joint_names.size(), 8u);
  EXPECT_EQ(f.limits.qd_max[at("left_j1")], 4.0);  // robot.yaml
  EXPECT_EQ(f.limits.qd_max[at("fl_pitch")], 20.0);  // the MJCF's joint user value
  EXPECT_TRUE(std::isinf(f.limits.qd_max[at("left_j2")]));
  EXPECT_EQ(f.limits.q_min[at("fl_pitch")], -2.0);
  EXPECT_EQ(f.limits.tau_max[at("rr_pitch")], 50.0);
  EXPECT_EQ(f.gain_group[at("fl_pitch")], "leg");
  EXPECT_EQ(f.gain_group[at("left_j1")], "other");
}

TEST_F(SyntheticRobot, LowPitchAuthorityIsWarned) {
  // The strongest stabilizer joint gives 0.028 kg m^2/s per rad/s, under 1 % of the robot's pitch inertia.
  const auto r = centaur::robot::checkRobot(centaur::robot::readRobotDescription(dir.path().string()));
  ASSERT_TRUE(r.problems.empty());
  ASSERT_EQ(r.warnings.size(), 2u);
  EXPECT_EQ(r.warnings[0].key, "stabilizers.raibert");
  EXPECT_EQ(r.warnings[1].key, "stabilizers.angmom");
  EXPECT_NE(r.warnings[1].message.find("'left_j1'"), std::string::npos) << r.warnings[1].message;
}

TEST(Centauro, ChecksWithoutWarnings) {
  // 93 kg with its stabilizers' strongest joint, the elbow, at 3.5 % of the pitch inertia per rad/s.
  const auto r = centaur::robot::checkRobot(centaur::robot::loadRobot("centauro"));
  EXPECT_TRUE(r.problems.empty());
  for (const auto& w : r.warnings) ADD_FAILURE() << w.text();
}

TEST(Centauro, DerivedTemplateIsThePresetLumpedByHand) {
  const RobotFacts f = centaur::robot::robotFacts(centaur::robot::loadRobot("centauro"));
  const auto preset = centaur::model::templatePreset("centauro");
  const auto& P = f.template_params;
  EXPECT_NEAR(f.total_mass, 93.113, 5e-4);
  EXPECT_EQ(f.joint_names.size(), 39u);
  EXPECT_NEAR(P.waist_mass, preset.waist_mass, 5e-4);
  EXPECT_NEAR(P.foot_mass, preset.foot_mass, 5e-4);
  // The measured CoM (0.1944, 0.0005, 0.2244): the preset rounds x and z to millimetres.
  EXPECT_NEAR(P.waist_com.x(), 0.1944, 5e-5);
  EXPECT_NEAR(P.waist_com.y(), 0.0005, 5e-5);
  EXPECT_NEAR(P.waist_com.z(), 0.2244, 5e-5);
  EXPECT_LT((P.waist_com - preset.waist_com).norm(), 1e-3);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(P.waist_inertia(i, i), preset.waist_inertia(i, i), 5e-4) << i;
  EXPECT_NEAR(P.waist_inertia(0, 2), preset.waist_inertia(0, 2), 5e-4);
  // The preset rounds the small products Ixy -0.009 and Iyz -0.013 to 0.
  EXPECT_NEAR(P.waist_inertia(0, 1), -0.009, 5e-4);
  EXPECT_NEAR(P.waist_inertia(1, 2), -0.013, 5e-4);
  for (int k = 0; k < 4; ++k) {
    EXPECT_LT((P.hip[k] - preset.hip[k]).norm(), 1e-9) << k;
    EXPECT_NEAR(f.foot_radius[k], 0.078, 1e-12);
  }
}

TEST(Centauro, MirrorSignsAndRaibertDirectionsAreTheOnesTypedToday) {
  const RobotFacts f = centaur::robot::robotFacts(centaur::robot::loadRobot("centauro"));
  ASSERT_EQ(f.arms.size(), 2u);
  const auto signs = centaur::data::armMirrorSigns();
  ASSERT_EQ(f.arms[1].mirror_signs.size(), 7u);
  for (int i = 0; i < 7; ++i) EXPECT_EQ(f.arms[1].mirror_signs[i], signs[i]) << i;
  // raibert.directions of the stabilizer's defaults (stabilizers/raibert_stabilizer.cpp), joints
  // j_arm1_1, j_arm2_1, j_arm1_4, j_arm2_4.
  EXPECT_EQ(f.raibert_directions, (std::vector<double>{-1.0, -1.0, 1.0, 1.0}));
  // The elbow's authority, ~0.64 kg m^2/s per rad/s (docs/robots.md): the stabilizers' lever.
  EXPECT_NEAR(std::abs(f.arms[0].pitch_authority[3]), 0.64, 0.05);
}

}  // namespace
