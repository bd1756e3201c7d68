// ctest-labels: unit
// Planner configuration: the shipped files document exactly the embedded defaults; bad values are refused
// with the file, key and range in the message.
#include <gtest/gtest.h>

#include "common/yaml_reader.hpp"
#include "model/template_params.hpp"
#include "planner/jump_config.hpp"
#include "robot/robot_registry.hpp"

using namespace centaur;
using namespace centaur::planner;

namespace {
std::string shipped(const std::string& name) { return std::string(CENTAUR_SOURCE_DIR) + "/config/" + name; }
}  // namespace

TEST(JumpConfig, ShippedFilesAreTheEmbeddedDefaults) {
  for (const std::string p : {"squat-jump", "half-squat-jump"}) {
    const YAML::Node defaults = loadYamlString(defaultJumpYaml(p), "<defaults>");
    const YAML::Node merged = mergeYaml(defaults, loadYamlFile(shipped(p + ".yaml")));
    EXPECT_EQ(toYamlString(merged), toYamlString(defaults)) << p;
  }
}

TEST(JumpConfig, DefaultsAreValidAndDescribeThePaperSettings) {
  const JumpConfig c = loadJumpConfig("squat-jump", "", {});
  EXPECT_EQ(c.horizon.intervals, 30);
  EXPECT_EQ(c.horizon.takeoff, 10);
  EXPECT_EQ(c.horizon.landing, 20);
  EXPECT_DOUBLE_EQ(c.horizon.dt_min, 0.03);
  EXPECT_DOUBLE_EQ(c.horizon.dt_max, 0.25);
  EXPECT_DOUBLE_EQ(c.cost.base_height, 50.0);
  EXPECT_DOUBLE_EQ(c.cost.joint_velocity, 1.0);
  EXPECT_DOUBLE_EQ(c.cost.force_rate, 1.0);
  EXPECT_DOUBLE_EQ(c.cost.acceleration_rate, 1e-3);
  EXPECT_DOUBLE_EQ(c.cost.last_interval, 1e-3);  // ours: the squat jump's robot rests through the last interval
  EXPECT_DOUBLE_EQ(c.cost.landing_steps, 0.0);   // ours, off: it moves the landing steps that are not free
  EXPECT_NEAR(c.initialWaistHeight(), 0.7188, 1e-9);
  EXPECT_NEAR(c.model.totalMass(), 93.113, 1e-9);
  const JumpConfig h = loadJumpConfig("half-squat-jump", "", {});
  EXPECT_DOUBLE_EQ(h.cost.base_pose, 50.0);
  EXPECT_DOUBLE_EQ(h.cost.last_interval, 0.0);  // its last interval sits at dt_max
  EXPECT_DOUBLE_EQ(h.cost.landing_steps, 0.0);
  EXPECT_NEAR(h.wallX(), -0.35 - 0.15 - 0.078, 1e-12);
}

TEST(JumpConfig, AuthorsSettingsLoad) {
  const JumpConfig c = loadJumpConfig("squat-jump", shipped("squat-jump-authors.yaml"), {});
  EXPECT_EQ(c.model.preset, "centauro-authors");
  EXPECT_NEAR(c.model.totalMass(), 109.0, 1e-9);
  EXPECT_DOUBLE_EQ(c.horizon.dt_max, 0.15);
  EXPECT_DOUBLE_EQ(c.contact.mu, 0.01);
  EXPECT_NEAR(c.initialWaistHeight(), 0.635, 1e-12);
  EXPECT_DOUBLE_EQ(c.cost.last_interval, 0.0);  // their cost: our additions are off
  EXPECT_DOUBLE_EQ(c.cost.landing_steps, 0.0);
}

TEST(JumpConfig, BadValuesNameTheKeyAndRange) {
  auto message = [](const std::vector<std::string>& sets) {
    try {
      loadJumpConfig("squat-jump", "", sets);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message({"horizon.intervals=2"}).find("horizon.intervals"), std::string::npos);
  EXPECT_NE(message({"contact.friction=square"}).find("pyramid, cone"), std::string::npos);
  EXPECT_NE(message({"model.preset=atlas"}).find("centauro-authors"), std::string::npos);
  EXPECT_NE(message({"model.waist_inertia=[1, 1, 1, 5, 0, 0]"}).find("positive definite"), std::string::npos);
  EXPECT_NE(message({"feet=[[0.35, 0.35, -0.2], [0.35, -0.35, -0.6], [-0.35, 0.35, -0.6], [-0.35, -0.35, -0.6]]"})
                .find("workspace"),
            std::string::npos);
  EXPECT_NE(message({"primitive=half-squat-jump"}).find("primitive"), std::string::npos);
  EXPECT_NE(message({"target.height=0.5"}).find("above the initial waist height"), std::string::npos);
  EXPECT_NE(message({"cost.unknown_term=1"}).find("cost.unknown_term"), std::string::npos);
  EXPECT_NE(message({"cost.last_interval=-1"}).find("cost.last_interval"), std::string::npos);
  EXPECT_NE(message({"cost.landing_steps=-1e-3"}).find("cost.landing_steps"), std::string::npos);
}

TEST(JumpConfig, RobotLayerPlansOnTheDerivedTemplateAndStanceAtHome) {
  const JumpConfig c = loadJumpConfig("squat-jump", "", {"robot=b2w_z1"});
  const auto robot = robot::loadRobotWithFacts("b2w_z1");
  EXPECT_EQ(c.robot, "b2w_z1");
  EXPECT_EQ(c.robot_hash, robot.description.hash);
  EXPECT_EQ(c.model.preset, "derived");
  EXPECT_EQ(c.model.waist_mass, robot.facts->template_params.waist_mass);
  EXPECT_EQ(c.model.waist_com, robot.facts->template_params.waist_com);
  for (int k = 0; k < 4; ++k) EXPECT_EQ(c.feet[k], robot.facts->b_p_foot[k]) << k;
  EXPECT_EQ(c.wheel_radius, robot.facts->foot_radius[0]);
  EXPECT_NEAR(c.initialWaistHeight(), robot.facts->home_base_height, 1e-9);  // the stance is the home posture
  EXPECT_DOUBLE_EQ(c.target_height, 0.78);  // models/b2w_z1/planner.yaml
  // A user's key still wins over the robot's layer.
  EXPECT_DOUBLE_EQ(loadJumpConfig("squat-jump", "", {"robot=b2w_z1", "target.height=0.8"}).target_height, 0.8);
}

TEST(JumpConfig, CentauroKeepsItsPresetAndStance) {
  const JumpConfig c = loadJumpConfig("half-squat-jump", "", {});
  const auto preset = model::templatePreset("centauro");
  EXPECT_EQ(c.robot, "centauro");
  EXPECT_EQ(c.model.preset, "centauro");
  EXPECT_EQ(c.model.waist_com, preset.waist_com);
  EXPECT_EQ(c.feet[0], Eigen::Vector3d(0.35, 0.35, -0.6408));
}

TEST(JumpConfig, BadRobotNamesTheKey) {
  try {
    loadJumpConfig("squat-jump", "", {"robot=no-such-robot"});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("key 'robot'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("centauro"), std::string::npos) << e.what();
  }
  EXPECT_THROW(loadJumpConfig("squat-jump", "", {"model.preset=derived", "robot=[1, 2]"}), InputError);
}
