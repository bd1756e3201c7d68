#include "robot_node/remote_controller.hpp"

#include <thread>

#include "common/error.hpp"
#include "controller/standing_controller.hpp"

namespace centaur::robot_node {

namespace mw = centaur::middleware;
using Clock = std::chrono::steady_clock;

namespace {

mw::JointLimits limitsOf(const sim::MujocoRobot& robot) {
  mw::JointLimits l;
  l.names = robot.jointNames();
  l.q_lo = robot.positionLower();
  l.q_hi = robot.positionUpper();
  l.tau_max = robot.effortLimits();
  return l;
}

std::int64_t toNs(double seconds) { return static_cast<std::int64_t>(seconds * 1e9); }

}  // namespace

RemoteController::RemoteController(const sim::MujocoRobot& robot, const mw::MiddlewareConfig& config,
                                   const mw::SafetyConfig& safety, const RemoteSettings& settings)
    : robot_(robot),
      safety_(safety),
      settings_(settings),
      participant_(config),
      joint_writer_(participant_, mw::kJointStates),
      imu_writer_(participant_, mw::kImu),
      forces_writer_(participant_, mw::kContactForces),
      status_writer_(participant_, mw::kRobotStatus),
      command_reader_(participant_, mw::kJointCommand),
      reset_reader_(participant_, mw::kRobotReset),
      waitset_(participant_),
      encoder_(robot.jointNames(), "imu_link"),
      guard_(limitsOf(robot), safety) {
  waitset_.attach(command_reader_.condition());
  const sim::SensorNoise& noise = robot.settings().noise;
  encoder_.setImuVariances(noise.orientation * noise.orientation, noise.gyro * noise.gyro, noise.acc * noise.acc);
  const Eigen::Index n = robot.numJoints();
  candidate_.resize(n);
  kd_damping_.resize(n);
  const StandingParams nominal;  // the robot's nominal gains per joint group (docs/sim.md)
  for (Eigen::Index i = 0; i < n; ++i) {
    kd_damping_[i] = safety_.damping_scale * gainsFor(robot.jointNames()[static_cast<std::size_t>(i)], nominal).kd;
  }
  bodies_ = robot.settings().contact_bodies;
  for (std::string& b : bodies_) body_ptrs_.push_back(b.data());
  force_msgs_.assign(bodies_.size(), mw::Vector3Msg{0.0, 0.0, 0.0});
  forces_.setZero(3, static_cast<Eigen::Index>(bodies_.size()));
  forces_msg_.header.frame_id = world_;
  forces_msg_.body = {static_cast<std::uint32_t>(bodies_.size()), static_cast<std::uint32_t>(bodies_.size()),
                      body_ptrs_.data(), false};
  forces_msg_.force = {static_cast<std::uint32_t>(bodies_.size()), static_cast<std::uint32_t>(bodies_.size()),
                       force_msgs_.data(), false};
}

RemoteController::~RemoteController() = default;

void RemoteController::setMode(std::uint8_t mode, const char* reason) noexcept {
  if (report_.mode == mode) return;
  report_.mode = mode;
  reason_ = reason;  // capacity reserved below: short literals only, no allocation after the first
  publishStatus(robot_.time(), true);
}

void RemoteController::publishState(const RobotState& state) noexcept {
  encoder_.encode(state);
  joint_writer_.write(encoder_.jointState());
  imu_writer_.write(encoder_.imu());
  robot_.contactForces(forces_);
  for (std::size_t k = 0; k < force_msgs_.size(); ++k) {
    const auto c = static_cast<Eigen::Index>(k);
    force_msgs_[k] = mw::Vector3Msg{forces_(0, c), forces_(1, c), forces_(2, c)};
  }
  forces_msg_.header.stamp = encoder_.jointState().header.stamp;
  forces_writer_.write(forces_msg_);
  ++report_.states_published;
}

void RemoteController::publishStatus(double t, bool force) noexcept {
  if (!force && settings_.status_decimation > 1 && periods_ % settings_.status_decimation != 0) return;
  const mw::GuardCounters& g = guard_.counters();
  mw::RobotStatusMsg s{};
  s.header.stamp = mw::timeFromNanoseconds(nanosecondsFromSeconds(t));
  s.header.frame_id = empty_;
  s.mode = report_.mode;
  s.lockstep = settings_.lockstep;
  s.reason = reason_.data();
  s.states_published = report_.states_published;
  s.commands_received = g.received + report_.ignored_in_damping;
  s.commands_applied = g.applied;
  s.commands_rejected = g.rejected;
  s.rejected_malformed = g.malformed;
  s.rejected_non_finite = g.non_finite;
  s.rejected_gains = g.gains;
  s.rejected_limits = g.limits;
  s.rejected_stale = g.stale;
  s.ignored_in_damping = report_.ignored_in_damping;
  s.references_clamped = g.clamped;
  s.late_periods = report_.late_periods;
  s.watchdog_trips = report_.watchdog_trips;
  s.last_applied_seq = guard_.lastAppliedSeq();
  s.last_command_age = report_.last_applied_time_s >= 0.0 ? t - report_.last_applied_time_s : -1.0;
  status_writer_.write(s);
}

bool RemoteController::receiveCommands(std::int64_t state_ns, JointCommand& command) noexcept {
  bool answered = false;
  command_reader_.take([&](const mw::JointCommandMsg& msg, const dds_sample_info_t&) {
    if (report_.mode == mw::kModeDamping) {
      ++report_.ignored_in_damping;
      return;
    }
    if (guard_.check(msg, state_ns, candidate_) != mw::Verdict::kApplied) return;
    command.q_ref = candidate_.q_ref;
    command.qd_ref = candidate_.qd_ref;
    command.tau_ff = candidate_.tau_ff;
    command.kp = candidate_.kp;
    command.kd = candidate_.kd;
    answered_ns_ = guard_.lastAppliedStateStamp();
    report_.last_applied_time_s = secondsFromNanoseconds(answered_ns_);
    answered = answered || answered_ns_ == state_ns;
  });
  return answered;
}

bool RemoteController::waitForAnswer(std::int64_t state_ns, JointCommand& command, double timeout_s) noexcept {
  const auto deadline = Clock::now() + std::chrono::nanoseconds(toNs(timeout_s));
  auto next_republish = Clock::now() + std::chrono::milliseconds(100);
  for (;;) {
    if (receiveCommands(state_ns, command)) return true;
    const auto now = Clock::now();
    if (now >= deadline) return false;
    if (now >= next_republish) {  // late subscribers (VOLATILE: a restarted controller) see the state again
      joint_writer_.write(encoder_.jointState());
      imu_writer_.write(encoder_.imu());
      publishStatus(robot_.time(), true);
      next_republish = now + std::chrono::milliseconds(100);
    }
    const auto until = std::min(deadline, next_republish);
    waitset_.wait(std::chrono::duration_cast<std::chrono::nanoseconds>(until - now).count());
  }
}

void RemoteController::writeDamping(const RobotState& state, JointCommand& command) const noexcept {
  command.q_ref = state.q;
  command.qd_ref.setZero();
  command.tau_ff.setZero();
  command.kp.setZero();
  command.kd = kd_damping_;
}

void RemoteController::enterDamping(const RobotState& state, JointCommand& command, const char* reason) noexcept {
  ++report_.watchdog_trips;
  if (report_.first_damping_time_s < 0.0) report_.first_damping_time_s = state.t;
  damping_wall0_ = Clock::now() - std::chrono::nanoseconds(nanosecondsFromSeconds(state.t));
  setMode(mw::kModeDamping, reason);
  writeDamping(state, command);
}

void RemoteController::pollReset() noexcept {
  bool reset = false;
  reset_reader_.take([&](const mw::EmptyMsg&, const dds_sample_info_t&) { reset = true; });
  if (!reset || report_.mode != mw::kModeDamping) return;
  ++report_.resets;
  watchdog_origin_s_ = robot_.time();  // the controller gets a fresh watchdog_timeout after a reset
  setMode(mw::kModeRunning, "reset");
}

void RemoteController::start(const RobotState& state, JointCommand& command) {
  reason_.reserve(96);
  report_.round_trip_us.reserve(settings_.record_round_trips);
  const std::int64_t ns = nanosecondsFromSeconds(state.t);
  publishStatus(state.t, true);
  publishState(state);
  if (!waitForAnswer(ns, command, settings_.connect_timeout)) {
    throw RuntimeError("robot: no valid command on " + participant_.rosName(mw::kJointCommand) + " within " +
                       std::to_string(settings_.connect_timeout) + " s (is `centaur control` running on domain " +
                       std::to_string(participant_.config().domain) + "?)");
  }
  watchdog_origin_s_ = state.t;
  setMode(mw::kModeRunning, "controller connected");
  wall0_ = Clock::now() - std::chrono::nanoseconds(ns);
  wall0_set_ = true;
}

void RemoteController::tick(const RobotState& state, JointCommand& command) noexcept {
  ++periods_;
  const std::int64_t ns = nanosecondsFromSeconds(state.t);
  pollReset();
  if (answered_ns_ == ns) {  // start() already has the answer to this state
    publishStatus(state.t, false);
    return;
  }
  if (!settings_.lockstep && wall0_set_) std::this_thread::sleep_until(wall0_ + std::chrono::nanoseconds(ns));
  const auto published = Clock::now();
  publishState(state);
  if (report_.mode == mw::kModeDamping) {
    // Nothing to lock to: a lockstep robot in damping mode paces itself at real time, so that a restarted
    // controller and a reset have time to come.
    if (settings_.lockstep) std::this_thread::sleep_until(damping_wall0_ + std::chrono::nanoseconds(ns));
    receiveCommands(ns, command);  // counted, ignored
    writeDamping(state, command);
    publishStatus(state.t, false);
    return;
  }
  if (settings_.lockstep) {
    if (!waitForAnswer(ns, command, settings_.lockstep_timeout)) {
      enterDamping(state, command, "watchdog: no command within lockstep_timeout");
    } else if (report_.round_trip_us.size() < settings_.record_round_trips) {
      report_.round_trip_us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - published).count());
    }
  } else {
    const auto period_start = wall0_ + std::chrono::nanoseconds(ns);
    const double left = settings_.command_wait -
                        std::chrono::duration<double>(Clock::now() - period_start).count();
    if (!waitForAnswer(ns, command, std::max(0.0, left))) ++report_.late_periods;
    const double since = std::max(report_.last_applied_time_s, watchdog_origin_s_);
    if (state.t - since > safety_.watchdog_timeout) {
      enterDamping(state, command, "watchdog: no valid command within safety.watchdog_timeout");
    }
  }
  publishStatus(state.t, false);
}

void RemoteController::finish() noexcept {
  setMode(mw::kModeFinished, "run ended");
  dds_wait_for_acks(status_writer_.get(), DDS_MSECS(500));
}

}  // namespace centaur::robot_node
