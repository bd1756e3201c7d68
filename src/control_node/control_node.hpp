#pragma once
// `centaur control <task>` (the executable centaur-control): the whole online stage as a middleware node.
// It runs the same controller `centaur simulate` runs in-process (stabilizers/online_stage.hpp), once per new
// robot state: sensor_msgs/JointState + sensor_msgs/Imu of one stamp in, centaur_msgs/JointCommand out
// (answering that stamp), centaur_msgs/ControllerStatus at status_decimation. It links neither Ipopt nor the
// simulator (tests/layering) and never plans: the primitive and the arm-flywheel plan come from files.
//
//   start     the controller starts on the first complete state; a jump's primitive starts after
//             --start-after S of settling, or (default) on a std_msgs/Empty on <ns>/start
//   stale     no new state for control_node.stale_time of wall time -> the controller's safe mode (hold the
//             posture with damping), status stale, reason stale_state; latched until <ns>/controller/reset
//   end       the robot's status says finished, SIGINT or SIGTERM -> exit 0
#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "controller/robot_interface.hpp"
#include "middleware/middleware_config.hpp"

namespace centaur::control_node {

struct ControlNodeSettings {
  double stale_time = 0.05;        ///< [s] wall time without a new state -> safe mode, [0.002, 60]
  /// [s] the same when the robot reports lockstep (a robot time that waits for us may be slow on a busy
  /// machine without being dead), [0.002, 600]
  double lockstep_stale_time = 2.0;
  double connect_timeout = 60.0;   ///< [s] wall time waiting for the first state, [0.1, 3600]
  int status_decimation = 10;      ///< controller status every N ticks (and on every change), [1, 10000]
};

/// What the node saw, for the summary and the tests.
struct ControlNodeReport {
  std::uint64_t ticks = 0, states_received = 0, states_rejected = 0, stale_events = 0, resets = 0;
  std::uint64_t commands_sent = 0;
  double tick_time_us_max = 0.0;
  bool finished = false;  ///< the robot reported the end of its run
};

struct ControlNodeArgs {
  std::string task;                    ///< stand | squat-jump | half-squat-jump
  std::string primitive_file;          ///< jumps: the primitive database (group named like the task)
  std::string stabilizer = "none";     ///< jumps
  std::string flywheel_file;           ///< jumps, ocp
  double start_after = -1.0;           ///< [s] jumps: start the primitive after this settle time (< 0: trigger)
  std::string config_file;
  std::vector<std::string> overrides;
};

/// The node's configuration defaults for a task: model, control_period, controller (the task's), middleware,
/// control_node sections (YAML text).
std::string controlNodeDefaultsYaml(const std::string& task);

/// Builds the controller (InputError for bad input, before any DDS entity exists) and runs the node until the
/// robot finishes or `stop` becomes true. RuntimeError if no state arrives within connect_timeout.
ControlNodeReport runControlNode(const ControlNodeArgs& args, const std::atomic<bool>& stop);

}  // namespace centaur::control_node
