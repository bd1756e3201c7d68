#pragma once
// RobotState <-> sensor_msgs/JointState + sensor_msgs/Imu, and JointCommand -> centaur_msgs/JointCommand.
// Doubles travel unchanged (the same bits arrive), times as whole nanoseconds (RobotState::t is a whole number
// of nanoseconds by construction, see robot_interface.hpp), quaternions in ROS order x, y, z, w.
// Encoders own every buffer their message points to (sized once in the constructor): encode() never allocates.
// Decoders check what arrives (untrusted): sizes, joint names and stamps; a message that does not fit is
// refused (false) and nothing of it is used.
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "controller/robot_interface.hpp"
#include "middleware/messages.hpp"

namespace centaur::middleware {

/// Robot side: the state as two ROS messages with the same stamp.
class StateEncoder {
 public:
  StateEncoder(const std::vector<std::string>& joint_names, const std::string& imu_frame);
  /// The Imu covariances: variances on the diagonal [rad^2, (rad/s)^2, (m/s^2)^2]; all zero (the default)
  /// means "unknown", the ROS convention.
  void setImuVariances(double orientation, double gyro, double acc);
  void encode(const RobotState& state);
  const JointStateMsg& jointState() const { return joints_; }
  const ImuMsg& imu() const { return imu_; }

 private:
  std::vector<std::string> names_;
  std::vector<char*> name_ptrs_;
  std::string imu_frame_;
  std::vector<double> q_, qd_, tau_;
  char empty_[1] = {'\0'};
  JointStateMsg joints_{};
  ImuMsg imu_{};
};

/// Controller side: joint states and IMU samples in, a RobotState out when both halves of one instant arrived.
class StateDecoder {
 public:
  /// `joint_names`: the controller model's order; the robot may send them in another order (mapped by name).
  explicit StateDecoder(const std::vector<std::string>& joint_names);
  /// False (and nothing changes) if the message has other joints, ragged arrays or an invalid stamp.
  bool acceptJoints(const JointStateMsg& msg);
  /// False if the stamp is invalid or the orientation is not a unit quaternion (|q| off by more than 1e-6).
  bool acceptImu(const ImuMsg& msg);
  /// True once the joint state and the IMU sample of one stamp, newer than the last taken, are both in.
  bool complete() const;
  /// Moves the completed state into `state` (sized n) and returns its stamp [ns].
  std::int64_t take(RobotState& state);
  std::int64_t lastTakenStamp() const { return taken_ns_; }

 private:
  bool mapNames(const JointStateMsg& msg);
  std::vector<std::string> names_;
  std::vector<int> index_;  // index_[i] = position in the message of our joint i
  std::vector<std::string> last_order_;
  RobotState joints_, imu_;
  std::int64_t joints_ns_ = -1, imu_ns_ = -1, taken_ns_ = -1;
};

/// Controller side: the command answering one state.
class CommandEncoder {
 public:
  CommandEncoder(const std::vector<std::string>& joint_names, std::uint64_t session);
  void encode(const JointCommand& command, std::int64_t state_ns);
  const JointCommandMsg& message() const { return msg_; }
  std::uint64_t session() const { return session_; }
  std::uint64_t seq() const { return seq_; }

 private:
  std::vector<std::string> names_;
  std::vector<char*> name_ptrs_;
  std::vector<double> q_ref_, qd_ref_, tau_ff_, kp_, kd_;
  char empty_[1] = {'\0'};
  std::uint64_t session_ = 0, seq_ = 0;
  JointCommandMsg msg_{};
};

}  // namespace centaur::middleware
