#pragma once
// `centaur robot <task>`: the simulated CENTAURO as a robot on the middleware. The task's simulation (world,
// duration, outcome metrics, log) runs as in `centaur simulate`, with the controller replaced by a
// RemoteController: states out, checked commands in (docs/middleware.md).
//
// Configuration: the task's simulation defaults (docs/sim.md) plus the sections `middleware:` (docs of
// middleware_config.hpp), `safety:` (command_guard.hpp) and `robot_node:` (below); the `controller:` section
// is the controller node's and is only saved with the outputs here.
#include <string>
#include <vector>

#include "robot_node/remote_controller.hpp"
#include "sim/sim_runner.hpp"

namespace centaur::robot_node {

struct RobotNodeArgs {
  std::string task;                    ///< stand | squat-jump | half-squat-jump
  std::string config_file;
  std::vector<std::string> overrides;  ///< "key=value"
  bool lockstep = false;               ///< else realtime
  std::string log_path;                ///< HDF5 log ("" = none)
  std::size_t record_round_trips = 0;  ///< keep this many round-trip times (benchmarks)
};

struct RobotNodeResult {
  sim::RunSummary summary;
  RemoteReport remote;
  bool lockstep = false;
  int domain = 0;
};

/// The `robot_node:` section's documented defaults.
const char* robotNodeDefaultsYaml();

/// Runs the task to its end. InputError for bad input (before any DDS entity is created), RuntimeError if no
/// controller connects within robot_node.connect_timeout.
RobotNodeResult runRobotNode(const RobotNodeArgs& args);

}  // namespace centaur::robot_node
