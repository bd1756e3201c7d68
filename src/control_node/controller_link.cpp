#include "control_node/controller_link.hpp"

#include <cstring>

#include "common/error.hpp"

namespace centaur::control_node {

namespace mw = centaur::middleware;
using Clock = std::chrono::steady_clock;

ControllerLink::ControllerLink(SupervisedController& controller, const mw::MiddlewareConfig& config,
                               const ControlNodeSettings& settings, std::string task, std::string stabilizer,
                               std::uint64_t session)
    : controller_(controller),
      settings_(settings),
      task_(std::move(task)),
      stabilizer_(std::move(stabilizer)),
      participant_(config),
      joint_reader_(participant_, mw::kJointStates),
      imu_reader_(participant_, mw::kImu),
      reset_reader_(participant_, mw::kControllerReset),
      start_reader_(participant_, mw::kStart),
      robot_status_reader_(participant_, mw::kRobotStatus),
      command_writer_(participant_, mw::kJointCommand),
      status_writer_(participant_, mw::kControllerStatus),
      waitset_(participant_),
      decoder_(controller.jointNames()),
      encoder_(controller.jointNames(), session) {
  for (dds_entity_t c : {joint_reader_.condition(), imu_reader_.condition(), reset_reader_.condition(),
                         start_reader_.condition(), robot_status_reader_.condition()}) {
    waitset_.attach(c);
  }
  const auto n = static_cast<Eigen::Index>(controller.jointNames().size());
  state_.resize(n);
  command_.resize(n);
  last_phase_.reserve(32);
}

void ControllerLink::takeInputs() {
  joint_reader_.take([&](const mw::JointStateMsg& m, const dds_sample_info_t&) {
    ++report_.states_received;
    if (!decoder_.acceptJoints(m)) ++report_.states_rejected;
  });
  imu_reader_.take([&](const mw::ImuMsg& m, const dds_sample_info_t&) {
    if (!decoder_.acceptImu(m)) ++report_.states_rejected;
  });
  start_reader_.take([&](const mw::EmptyMsg&, const dds_sample_info_t&) { trigger_pending_ = true; });
  reset_reader_.take([&](const mw::EmptyMsg&, const dds_sample_info_t&) { reset_pending_ = true; });
  robot_status_reader_.take([&](const mw::RobotStatusMsg& m, const dds_sample_info_t&) {
    if (m.mode == mw::kModeFinished && started_) report_.finished = true;
    robot_lockstep_ = m.lockstep;
    robot_status_seen_ = true;
  });
}

// The first tick waits for the robot's status: only then is it known which stale time applies (a lockstep robot
// on a busy machine may take longer than stale_time per period). The robot publishes its status before its first
// state and again every 100 ms while it waits for the first answer; a robot that publishes no status at all
// is served after kStatusGrace, then judged by stale_time.
bool ControllerLink::readyToStart() {
  constexpr double kStatusGrace = 1.0;  // [s] wall time
  if (started_ || robot_status_seen_) return true;
  if (!decoder_.complete()) return false;
  if (!first_state_seen_) {
    first_state_seen_ = true;
    first_state_wall_ = Clock::now();
  }
  return std::chrono::duration<double>(Clock::now() - first_state_wall_).count() >= kStatusGrace;
}

void ControllerLink::tickOnce(std::int64_t state_ns) {
  if (!started_) {
    controller_.start(state_, command_);  // may allocate or throw (bad robot): before the loop proper
    started_ = true;
  }
  if (trigger_pending_) {
    controller_.triggerStart(state_.t);
    trigger_pending_ = false;
  }
  if (reset_pending_) {
    controller_.resume();
    node_safe_reason_ = "";
    stale_ = false;
    reset_pending_ = false;
    ++report_.resets;
  }
  const auto t0 = Clock::now();
  controller_.tick(state_, command_);
  tick_us_ = std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
  report_.tick_time_us_max = std::max(report_.tick_time_us_max, tick_us_);
  ++report_.ticks;
  encoder_.encode(command_, state_ns);
  if (command_writer_.write(encoder_.message())) ++report_.commands_sent;
  last_state_ns_ = state_ns;
  last_state_wall_ = Clock::now();
  const bool was_stale = stale_;
  stale_ = false;  // states flow again; the safe mode the staleness caused stays until a reset
  publishStatus(was_stale);
}

void ControllerLink::checkStale() {
  if (!started_ || stale_) return;
  const double since = std::chrono::duration<double>(Clock::now() - last_state_wall_).count();
  if (since <= (robot_lockstep_ ? settings_.lockstep_stale_time : settings_.stale_time)) return;
  stale_ = true;
  ++report_.stale_events;
  node_safe_reason_ = "stale_state";
  controller_.requestSafeMode();  // latched until <ns>/controller/reset
  publishStatus(true);
}

void ControllerLink::publishStatus(bool force) {
  const ControllerReport r = controller_.report();
  const bool changed = last_safe_ != r.safe_mode || last_phase_ != r.phase;
  if (!force && !changed && settings_.status_decimation > 1 && report_.ticks % settings_.status_decimation != 0) {
    return;
  }
  last_safe_ = r.safe_mode;
  last_phase_ = r.phase;
  const bool node_safe = node_safe_reason_[0] != '\0';
  mw::ControllerStatusMsg s{};
  s.header.stamp = mw::timeFromNanoseconds(last_state_ns_ < 0 ? 0 : last_state_ns_);
  s.header.frame_id = empty_;
  s.session = encoder_.session();
  s.task = task_.data();
  s.stabilizer = stabilizer_.data();
  s.phase = const_cast<char*>(r.phase);
  s.safe_mode = r.safe_mode || node_safe;
  s.safe_reason = const_cast<char*>(node_safe ? node_safe_reason_ : r.safe_reason);
  s.stale = stale_;
  for (int k = 0; k < 4; ++k) contact_[k] = r.stance[static_cast<std::size_t>(k)];
  s.contact = {4, 4, contact_, false};
  s.tick_time_us = tick_us_;
  s.tick_time_us_max = report_.tick_time_us_max;
  s.ticks = report_.ticks;
  s.states_received = report_.states_received;
  s.states_rejected = report_.states_rejected;
  s.stale_events = report_.stale_events;
  status_writer_.write(s);
}

ControlNodeReport ControllerLink::run(const std::atomic<bool>& stop) {
  const auto begin = Clock::now();
  while (!stop.load() && !report_.finished) {
    const auto wait = std::chrono::duration<double>(started_ ? std::min(settings_.stale_time, 0.1) : 0.1);
    waitset_.wait(std::chrono::duration_cast<std::chrono::nanoseconds>(wait).count());
    takeInputs();
    while (readyToStart() && decoder_.complete()) tickOnce(decoder_.take(state_));
    checkStale();
    if (!started_ && std::chrono::duration<double>(Clock::now() - begin).count() > settings_.connect_timeout) {
      throw RuntimeError("control: no robot state on " + participant_.rosName(mw::kJointStates) + " within " +
                         std::to_string(settings_.connect_timeout) + " s (is `centaur robot` running on domain " +
                         std::to_string(participant_.config().domain) + "?)");
    }
  }
  publishStatus(true);
  dds_wait_for_acks(status_writer_.get(), DDS_MSECS(200));
  return report_;
}

}  // namespace centaur::control_node
