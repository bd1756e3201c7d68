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
// Scenario-specific metrics/outcome: set Scenario::make_observer to return a RunObserver.
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
  bool input_file = false;           ///< the value names a file the run reads (no output may overwrite it)
};

/// What a controller factory receives.
struct ScenarioContext {
  const SimConfig& config;                          ///< the effective configuration
  YamlReader& controller_config;                    ///< strict reader of `controller:`; read keys, then finish()
  const std::map<std::string, std::string>& options;  ///< scenario options by name (defaults filled in)
  MujocoRobot& robot;                               ///< reset to the initial state; may be adjusted
};

/// Optional per-scenario bookkeeping: sees every control period (ground truth included) and adds its
/// own numbers to the summary (and to `--json`), e.g. apex height or wall contact for a jump.
class RunObserver {
 public:
  virtual ~RunObserver() = default;
  /// After each control period (robot: ground truth; state/command: what the controller saw/sent).
  virtual void observe(const MujocoRobot& robot, const RobotState& state, const JointCommand& command) = 0;
  /// Extra summary values (name -> number), added to RunSummary::extra and the JSON line.
  virtual std::map<std::string, double> summary() const { return {}; }
  /// "" keeps the runner's outcome ("success"/"fall"); anything else replaces "success" (e.g.
  /// "no_wall_contact"); a fall stays a fall.
  virtual std::string outcome() const { return ""; }
};

struct Scenario {
  std::string name;
  std::string help;
  std::string defaults_yaml;  ///< scenario defaults merged over the simulation defaults (duration, controller)
  std::vector<ScenarioOption> options;
  std::function<std::unique_ptr<Controller>(ScenarioContext&)> make_controller;
  /// Optional (may be empty): created after the controller, with the same context.
  std::function<std::unique_ptr<RunObserver>(ScenarioContext&)> make_observer = nullptr;
  /// Optional (may be empty): reads the `controller:` section as make_controller would, strictly and without
  /// building anything (no model, no plan), so that a batch can check its overrides before it starts.
  /// Throws InputError naming the key.
  std::function<void(YamlReader& controller_config)> check_controller = nullptr;
};

/// All scenarios (the built-in `stand`, `squat-jump`, `half-squat-jump` first, then every ScenarioRegistrar in registration order).
std::vector<Scenario>& scenarios();
/// nullptr if unknown.
const Scenario* findScenario(const std::string& name);

struct ScenarioRegistrar {
  explicit ScenarioRegistrar(Scenario s) { scenarios().push_back(std::move(s)); }
};

/// The built-in standing scenario (StandingController, defined in scenario_stand.cpp).
Scenario standScenario();
/// The built-in jumps (JumpController + stabilizer, scenario_jump.cpp): "squat-jump", "half-squat-jump".
Scenario squatJumpScenario();
Scenario halfSquatJumpScenario();

}  // namespace centaur::sim
