#pragma once
// Where robots come from: `--robot NAME|PATH`. A NAME is a folder of <source>/models/ holding a robot.yaml
// (the shipped robots; listed, never typed as a literal list anywhere); a PATH is a robot.yaml or a folder with
// one. The default robot is kDefaultRobot, in this one place.
#include <string>
#include <vector>

#include <memory>

#include "robot/robot_description.hpp"
#include "robot/robot_facts.hpp"

namespace centaur::robot {

inline constexpr const char* kDefaultRobot = "centauro";

/// <source>/models, where the shipped robots live.
std::string modelsDirectory();
/// The shipped robots: sub-folders of modelsDirectory() with a robot.yaml, sorted.
std::vector<std::string> robotNames();
/// The robot.yaml that `name_or_path` means; InputError naming the shipped robots if it means none.
std::string robotYamlPath(const std::string& name_or_path);
/// readRobotDescription(robotYamlPath(name_or_path)).
RobotDescription loadRobot(const std::string& name_or_path);

/// A robot and its facts, derived once per process for each description (same file, same hash): configurations
/// of many primitives (a sweep) share one derivation. InputError listing every problem of a broken robot.
struct LoadedRobot {
  RobotDescription description;
  std::shared_ptr<const RobotFacts> facts;
};
LoadedRobot loadRobotWithFacts(const std::string& name_or_path);

}  // namespace centaur::robot
