#pragma once
// Simulation scenarios: a name, documented defaults, scenario options and a controller factory.
// `centaur simulate <scenario>` is built from this registry (src/cli/cmd_simulate.cpp): every registered
// scenario becomes a sub-command with the common options (--duration --config --set --out --video
// --snapshot --at --json) plus its own ScenarioOptions (e.g. --primitive F.h5 --stabilizer raibert).
//
// Adding a scenario (e.g. squat-jump) without touching existing files:
//   // src/cli/sim_squat_jump.cpp  (compiled into the `centaur` executable, so its registrar runs)
//   static centaur::sim::ScenarioRegistrar reg{centaur::sim::Scenario{
//       "squat-jump", "replay a squat-jump primitive with a stabilizer",
//       R"(duration: 4.0
//          controller: {stabilizer_gain: 1.0})",                      // documented defaults (YAML)
//       {{"primitive", "primitive file (HDF5)", "", {}, true},
//        {"stabilizer", "balance stabilizer", "none", {"none", "raibert", "angmom", "ocp"}, false}},
//       [](centaur::sim::ScenarioContext& ctx) -> std::unique_ptr<centaur::Controller> {
//         auto cfg = ctx.controller_config;   // strict reader of the `controller:` section
//         ... read keys, cfg.finish(); build the controller from ctx.model_path and ctx.options ...
//       }}};
// (A registrar inside the static library centaur_sim would be dropped by the linker unless something
// references its object file; the built-in `stand` is therefore added by scenarios() itself.)
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "common/yaml_reader.hpp"
#include "controller/robot_interface.hpp"
#include "sim/mujoco_robot.hpp"
#include "sim/sim_config.hpp"

namespace centaur::sim {

/// A scenario-specific command-line option `--<name> VALUE`.
struct ScenarioOption {
  std::string name;                  ///< without dashes, e.g. "primitive"
  std::string help;
  std::string default_value;         ///< used when the option is absent
  std::vector<std::string> allowed;  ///< empty = any value
  bool required = false;
};

/// What a controller factory receives.
struct ScenarioContext {
  const SimConfig& config;                          ///< the effective configuration
  YamlReader& controller_config;                    ///< strict reader of `controller:`; read keys, then finish()
  const std::map<std::string, std::string>& options;  ///< scenario options by name (defaults filled in)
  MujocoRobot& robot;                               ///< reset to the initial state; may be adjusted
};

struct Scenario {
  std::string name;
  std::string help;
  std::string defaults_yaml;  ///< scenario defaults merged over the simulation defaults (duration, controller)
  std::vector<ScenarioOption> options;
  std::function<std::unique_ptr<Controller>(ScenarioContext&)> make_controller;
};

/// All scenarios (the built-in `stand` first, then every ScenarioRegistrar in registration order).
std::vector<Scenario>& scenarios();
/// nullptr if unknown.
const Scenario* findScenario(const std::string& name);

struct ScenarioRegistrar {
  explicit ScenarioRegistrar(Scenario s) { scenarios().push_back(std::move(s)); }
};

/// The built-in standing scenario (StandingController, defined in scenario_stand.cpp).
Scenario standScenario();

}  // namespace centaur::sim
