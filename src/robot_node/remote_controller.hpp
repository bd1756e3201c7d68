#pragma once
// The robot side of the wire: a Controller whose tick() publishes the measured state on the middleware and
// applies the command that comes back, after the CommandGuard has checked it. The simulator loop
// (sim::runSimulation) runs it exactly like an in-process controller, so the physics, the 2 kHz impedance
// law, the log and the outcome are the simulator's own; only the controller is elsewhere.
//
// Modes (centaur_msgs/RobotStatus.mode):
//   waiting   before the first valid command: start() publishes the first state (again every 100 ms of wall
//             time, for late subscribers) and waits up to `connect_timeout`; robot time does not advance.
//   running   every period: publish the state, apply the valid command that answers it.
//     lockstep: wait (wall clock, up to `lockstep_timeout`) for the command answering this state; robot time
//               only advances when it arrives: deterministic, as fast as both processes allow.
//     realtime: robot time follows the wall clock (1x); wait for the answer until `command_wait` after the
//               period began; a command that has not arrived keeps the previous one and counts as late.
//   damping   no valid command for `safety.watchdog_timeout` of robot time (realtime) or `lockstep_timeout`
//             of wall time (lockstep): kp = 0, kd = damping_scale x nominal kd, qd_ref = 0 and tau_ff = 0 (no
//             gravity feed-forward: a stale model must not push); latched until a std_msgs/Empty on
//             <ns>/robot/reset, after which the next valid command resumes (lockstep: is waited for again).
//             Commands arriving meanwhile are counted and ignored; a lockstep robot paces itself at 1x.
//   finished  the run ended (published by finish()).
// tick() never throws; start() throws RuntimeError if no controller answers within connect_timeout.
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "controller/robot_interface.hpp"
#include "middleware/command_guard.hpp"
#include "middleware/dds.hpp"
#include "middleware/messages.hpp"
#include "middleware/state_codec.hpp"
#include "sim/mujoco_robot.hpp"

namespace centaur::robot_node {

struct RemoteSettings {
  bool lockstep = true;
  double lockstep_timeout = 2.0;  ///< [s] wall time waiting for one answer in lockstep -> damping
  double connect_timeout = 60.0;  ///< [s] wall time waiting for the first valid command
  double command_wait = 0.0008;   ///< [s] realtime: how long after the period began a command may arrive
  int status_decimation = 10;     ///< robot status every N periods (and on every mode change)
  std::size_t record_round_trips = 0;  ///< keep up to this many state -> command round-trip times (benchmarks)
};

/// What the robot side did, for the summary and the tests.
struct RemoteReport {
  middleware::GuardCounters guard;
  std::uint64_t states_published = 0, ignored_in_damping = 0, late_periods = 0, watchdog_trips = 0, resets = 0;
  double first_damping_time_s = -1.0;   ///< robot time of the first period in damping mode (-1: never)
  double last_applied_time_s = -1.0;    ///< robot time of the state the last applied command answered
  std::uint8_t mode = middleware::kModeWaiting;
  /// [us] wall time from publishing a state to applying the command that answers it (when recorded)
  std::vector<double> round_trip_us;
};

class RemoteController final : public Controller {
 public:
  RemoteController(const sim::MujocoRobot& robot, const middleware::MiddlewareConfig& mw,
                   const middleware::SafetyConfig& safety, const RemoteSettings& settings);
  ~RemoteController() override;

  void start(const RobotState& state, JointCommand& command) override;
  void tick(const RobotState& state, JointCommand& command) noexcept override;
  /// Publish the final status (mode finished) so that the controller node can stop.
  void finish() noexcept;
  /// What happened so far (the guard's counters included).
  RemoteReport report() const {
    RemoteReport r = report_;
    r.guard = guard_.counters();
    return r;
  }

 private:
  bool receiveCommands(std::int64_t state_ns, JointCommand& command) noexcept;
  /// Waits for the valid command answering `state_ns`, publishing the state again every 100 ms of wall time.
  bool waitForAnswer(std::int64_t state_ns, JointCommand& command, double timeout_s) noexcept;
  void enterDamping(const RobotState& state, JointCommand& command, const char* reason) noexcept;
  void writeDamping(const RobotState& state, JointCommand& command) const noexcept;
  void pollReset() noexcept;
  void publishState(const RobotState& state) noexcept;
  void publishStatus(double t, bool force) noexcept;
  void setMode(std::uint8_t mode, const char* reason) noexcept;

  const sim::MujocoRobot& robot_;
  middleware::SafetyConfig safety_;
  RemoteSettings settings_;
  middleware::Participant participant_;
  middleware::Writer<middleware::JointStateMsg> joint_writer_;
  middleware::Writer<middleware::ImuMsg> imu_writer_;
  middleware::Writer<middleware::ContactForcesMsg> forces_writer_;
  middleware::Writer<middleware::RobotStatusMsg> status_writer_;
  middleware::Reader<middleware::JointCommandMsg> command_reader_;
  middleware::Reader<middleware::EmptyMsg> reset_reader_;
  middleware::WaitSet waitset_;
  middleware::StateEncoder encoder_;
  middleware::CommandGuard guard_;
  JointCommand candidate_;
  Eigen::VectorXd kd_damping_;
  Eigen::Matrix3Xd forces_;
  std::vector<middleware::Vector3Msg> force_msgs_;
  std::vector<std::string> bodies_;
  std::vector<char*> body_ptrs_;
  middleware::ContactForcesMsg forces_msg_{};
  char world_[6] = "world";
  char empty_[1] = {'\0'};
  std::string reason_ = "started";
  RemoteReport report_;
  std::int64_t answered_ns_ = -1;  // state stamp the current command answers
  double watchdog_origin_s_ = 0.0;  // robot time the watchdog counts from (connection, reset)
  std::int64_t periods_ = 0;
  std::chrono::steady_clock::time_point wall0_, damping_wall0_;
  bool wall0_set_ = false;
};

}  // namespace centaur::robot_node
