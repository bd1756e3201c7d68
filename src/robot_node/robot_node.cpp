#include "robot_node/robot_node.hpp"

#include <algorithm>
#include <map>

#include "common/error.hpp"
#include "common/output_guard.hpp"
#include "common/yaml_reader.hpp"
#include "sim/scenario.hpp"
#include "stabilizers/online_stage.hpp"

namespace centaur::robot_node {

const char* robotNodeDefaultsYaml() {
  return R"(robot_node:                  # the simulated robot on the middleware (docs/middleware.md)
  lockstep_timeout: 2.0       # [s] lockstep: wall time waiting for the answer to one state -> damping, [0.001, 600]
  connect_timeout: 60.0       # [s] wall time waiting for the first valid command, [0.1, 3600]
  command_wait: 0.0008        # [s] realtime: a command may arrive until this long after its period began, [0, 0.01]
  status_decimation: 10       # robot status every N control periods (and on every mode change), [1, 10000]
)";
}

namespace {

RemoteSettings readSettings(const sim::SimConfig& config, bool lockstep) {
  RemoteSettings s;
  s.lockstep = lockstep;
  YamlReader r(config.effective["robot_node"], config.label, "robot_node");
  r.get("lockstep_timeout", s.lockstep_timeout, 0.001, 600.0);
  r.get("connect_timeout", s.connect_timeout, 0.1, 3600.0);
  r.get("command_wait", s.command_wait, 0.0, 0.01);
  r.get("status_decimation", s.status_decimation, 1, 10000);
  r.finish();
  if (!lockstep && s.command_wait >= config.robot.timestep * config.robot.control_decimation) {
    r.fail("command_wait", "must be shorter than the control period");
  }
  return s;
}

}  // namespace

RobotNodeResult runRobotNode(const RobotNodeArgs& a) {
  const auto& tasks = onlineTasks();
  const sim::Scenario* scenario = sim::findScenario(a.task);
  if (scenario == nullptr || std::find(tasks.begin(), tasks.end(), a.task) == tasks.end()) {
    throw InputError("robot: task '" + a.task + "' is not available (stand, squat-jump, half-squat-jump)");
  }
  const std::string defaults = scenario->defaults_yaml + "\n" + middleware::MiddlewareConfig::defaultsYaml() +
                               middleware::SafetyConfig::defaultsYaml() + robotNodeDefaultsYaml();
  const sim::SimConfig config =
      sim::loadSimConfig(defaults, a.config_file, a.overrides, {"middleware", "safety", "robot_node"});
  middleware::MiddlewareConfig mw;
  {
    YamlReader r(config.effective["middleware"], config.label, "middleware");
    mw.read(r);
  }
  middleware::SafetyConfig safety;
  {
    YamlReader r(config.effective["safety"], config.label, "safety");
    safety.read(r);
  }
  RemoteSettings settings = readSettings(config, a.lockstep);
  sim::RunOutputs outputs;
  outputs.log_path = a.log_path;
  // Before anything is written: the log and its effective configuration must not overwrite an input.
  guardOutputs({{"--config", a.config_file}, {"model", config.robot.model_path}}, sim::runOutputFiles(outputs));
  settings.record_round_trips = a.record_round_trips;
  sim::SimSettings robot_settings = config.robot;
  robot_settings.visual_geoms = false;
  sim::MujocoRobot robot(robot_settings);
  RemoteController remote(robot, mw, safety, settings);
  YamlReader controller_section = sim::controllerSection(config);  // the controller node's: not read here
  const std::map<std::string, std::string> no_options;
  sim::ScenarioContext ctx{config, controller_section, no_options, robot};
  std::unique_ptr<sim::RunObserver> observer = scenario->make_observer ? scenario->make_observer(ctx) : nullptr;
  RobotNodeResult result;
  result.summary = sim::runSimulation(robot, remote, config, outputs, a.task, observer.get());
  remote.finish();
  result.remote = remote.report();
  result.lockstep = a.lockstep;
  result.domain = mw.domain;
  return result;
}

}  // namespace centaur::robot_node
