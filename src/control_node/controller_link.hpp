#pragma once
// The controller node's loop: couples one SupervisedController to the middleware (see control_node.hpp for
// the behaviour). Everything is allocated in the constructor and at the first state; a tick's path (decode,
// tick, encode, write) allocates nothing on our side.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>

#include "control_node/control_node.hpp"
#include "middleware/dds.hpp"
#include "middleware/messages.hpp"
#include "middleware/state_codec.hpp"

namespace centaur::control_node {

class ControllerLink {
 public:
  ControllerLink(SupervisedController& controller, const middleware::MiddlewareConfig& mw,
                 const ControlNodeSettings& settings, std::string task, std::string stabilizer, std::uint64_t session);
  /// Until the robot finishes or `stop`; RuntimeError if no state arrives within connect_timeout.
  ControlNodeReport run(const std::atomic<bool>& stop);

 private:
  void takeInputs();
  void tickOnce(std::int64_t state_ns);
  void checkStale();
  bool readyToStart();
  void publishStatus(bool force);

  SupervisedController& controller_;
  ControlNodeSettings settings_;
  std::string task_, stabilizer_;
  middleware::Participant participant_;
  middleware::Reader<middleware::JointStateMsg> joint_reader_;
  middleware::Reader<middleware::ImuMsg> imu_reader_;
  middleware::Reader<middleware::EmptyMsg> reset_reader_, start_reader_;
  middleware::Reader<middleware::RobotStatusMsg> robot_status_reader_;
  middleware::Writer<middleware::JointCommandMsg> command_writer_;
  middleware::Writer<middleware::ControllerStatusMsg> status_writer_;
  middleware::WaitSet waitset_;
  middleware::StateDecoder decoder_;
  middleware::CommandEncoder encoder_;
  RobotState state_;
  JointCommand command_;
  ControlNodeReport report_;
  bool started_ = false, stale_ = false, trigger_pending_ = false, reset_pending_ = false;
  bool robot_lockstep_ = false;  // the robot's status says lockstep (see lockstep_stale_time)
  bool robot_status_seen_ = false;  // its mode is known: the stale time to apply is known
  bool first_state_seen_ = false;
  std::chrono::steady_clock::time_point first_state_wall_;
  const char* node_safe_reason_ = "";  // set when the node itself asked for the safe mode
  std::string last_phase_;
  bool last_safe_ = false;
  double tick_us_ = 0.0;
  std::int64_t last_state_ns_ = -1;
  std::chrono::steady_clock::time_point last_state_wall_;
  bool contact_[4] = {false, false, false, false};
  char empty_[1] = {'\0'};
};

}  // namespace centaur::control_node
