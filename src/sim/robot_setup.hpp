#pragma once
// The simulated robot from its description (robot/): the scene centaur builds around a robot-alone MJCF, the
// robot's layer of a simulation configuration, and the names the online stage needs (RobotFrames).
#include <yaml-cpp/yaml.h>

#include <memory>
#include <string>

#include "controller/robot_frames.hpp"
#include "robot/robot_registry.hpp"

namespace centaur::sim {

struct SimRobot {
  robot::RobotDescription description;
  std::shared_ptr<const robot::RobotFacts> facts;
  RobotFrames frames;
};

/// The robot `name_or_path` (robot/robot_registry.hpp) with its facts and frames; InputError for a broken one.
SimRobot loadSimRobot(const std::string& name_or_path);

/// The world centaur adds around a robot-alone MJCF: an MJCF that includes it, with the ground (geom `ground`),
/// the wall (body and geom `wall`, moved by world.wall_x), a light, the camera `side` and the offscreen size.
std::string sceneXml(const robot::RobotDescription& d);

/// What the robot brings to a simulation configuration (between the scenario's defaults and the user's file):
/// the pushed body (its base), the fall height (half its home base height, down to 5 cm), the wall 0.15 m behind
/// its rear feet, and, for a controller section that has them, its foot radius, its impedance groups (which
/// replace the defaults' `controller.gains`) and its Raibert joints with their derived directions (gains: the
/// defaults' when they are as many, else 1). `defaults` is the configuration it goes onto.
YAML::Node simRobotLayer(const SimRobot& r, const YAML::Node& defaults);

}  // namespace centaur::sim
