#pragma once
// Scenario configuration of a simulation run (YAML). Documented defaults, units and ranges are in
// kSimConfigDefaults below (and docs/sim.md); unknown keys are errors (InputError naming file and key).
// The `controller:` section belongs to the scenario's controller and is read by it (see scenario.hpp).
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "common/yaml_reader.hpp"
#include "controller/robot_frames.hpp"
#include "sim/mujoco_robot.hpp"

namespace centaur::sim {

/// The documented defaults (YAML text, with units and ranges in comments).
extern const char* const kSimConfigDefaults;

struct RenderSettings {
  int width = 640;            ///< [px]
  int height = 480;           ///< [px]
  double fps = 30.0;          ///< [1/s] video frame rate
  std::string camera = "side";  ///< MJCF camera name; "" or missing -> a free camera tracking the pelvis
  bool shadows = true;          ///< render shadows (slow in software GL)
  bool reflections = false;     ///< render floor reflections (slow in software GL)
};

struct OutcomeSettings {
  double fall_height = 0.35;    ///< [m] pelvis height below which the run is a fall
  double fall_tilt_deg = 45.0;  ///< [deg] |roll| or |pitch| above which the run is a fall
};

struct SimConfig {
  double duration = 10.0;   ///< [s]
  SimSettings robot;        ///< physics, world, sensors
  std::string robot_name = "centauro";  ///< key robot.name: the description's name (robot/)
  std::string robot_hash;               ///< its description's hash
  RobotFrames frames;                   ///< the names the online stage needs (from the description)
  RenderSettings render;
  OutcomeSettings outcome;
  int log_decimation = 1;   ///< log every N-th control period
  YAML::Node effective;     ///< the whole effective configuration (defaults + file + overrides)
  std::string label;        ///< where it came from (file name or "<defaults>"), for messages
};

/// Build the effective configuration: embedded defaults <- `scenario_defaults` (YAML text, e.g. the
/// scenario's controller section and duration) <- file (if not empty) <- `--set key=value` overrides.
/// Reads and range-checks every key except `controller` (returned in `controller`, for the scenario) and the
/// `node_sections` (e.g. "middleware", "safety" of the robot node, which reads them from `effective`).
/// Throws InputError naming the file, key and allowed range.
SimConfig loadSimConfig(const std::string& scenario_defaults, const std::string& file,
                        const std::vector<std::string>& overrides, const std::vector<std::string>& node_sections = {});

/// A strict reader of the `controller:` section (prefix "controller"), for the scenario's controller.
YamlReader controllerSection(const SimConfig& config);

/// Parse the non-controller sections of an already merged node (used by loadSimConfig, which then fills in what
/// comes from the robot: an empty `model` becomes the robot's MJCF).
SimConfig parseSimConfig(const YAML::Node& effective, const std::string& label,
                         const std::vector<std::string>& node_sections = {});


}  // namespace centaur::sim
