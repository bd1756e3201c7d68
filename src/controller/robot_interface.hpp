#pragma once
// The only door between the controller and a robot (simulated or real).
// The controller reads a RobotState and writes a JointCommand; the robot side runs the joint impedance law
//   tau = tau_ff + kp (q_ref - q) + kd (qd_ref - qd),  saturated at the joint effort limits,
// at its own rate (2 kHz in simulation). Joint order: the robot model's actuated-joint order
// (RobotModel::jointNames()). Nothing here knows about any simulator.
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace centaur {

/// The robot clock counts whole nanoseconds (as a middleware timestamp does): RobotState::t is
/// secondsFromNanoseconds(n) for an integer n, so a state sent over the wire arrives with the same t, bit for bit.
inline double secondsFromNanoseconds(std::int64_t ns) { return static_cast<double>(ns) * 1e-9; }
/// The nearest whole nanosecond of `t` [s].
inline std::int64_t nanosecondsFromSeconds(double t) { return std::llround(t * 1e9); }

/// What the robot measures. Sized once (resize(n)); never reallocated in the loop.
struct RobotState {
  double t = 0.0;                  ///< [s] robot time, a whole number of nanoseconds (secondsFromNanoseconds)
  Eigen::VectorXd q;               ///< [rad] joint positions (n)
  Eigen::VectorXd qd;              ///< [rad/s] joint velocities (n)
  Eigen::VectorXd tau;             ///< [Nm] measured joint torques (n)
  Eigen::Quaterniond imu_quat = Eigen::Quaterniond::Identity();  ///< w_R_imu (Eigen storage: x,y,z,w)
  Eigen::Vector3d imu_omega = Eigen::Vector3d::Zero();  ///< [rad/s] angular velocity in the IMU frame
  Eigen::Vector3d imu_acc = Eigen::Vector3d::Zero();    ///< [m/s^2] specific force in the IMU frame

  void resize(Eigen::Index n) {
    q.setZero(n);
    qd.setZero(n);
    tau.setZero(n);
  }
};

/// What the controller commands, per joint. Sized once (resize(n)).
struct JointCommand {
  Eigen::VectorXd q_ref;   ///< [rad]
  Eigen::VectorXd qd_ref;  ///< [rad/s]
  Eigen::VectorXd tau_ff;  ///< [Nm] torque feed-forward
  Eigen::VectorXd kp;      ///< [Nm/rad]
  Eigen::VectorXd kd;      ///< [Nm s/rad]

  void resize(Eigen::Index n) {
    q_ref.setZero(n);
    qd_ref.setZero(n);
    tau_ff.setZero(n);
    kp.setZero(n);
    kd.setZero(n);
  }
};

/// A robot: read sensors, write joint references.
class RobotInterface {
 public:
  virtual ~RobotInterface() = default;
  virtual Eigen::Index numJoints() const = 0;
  virtual void read(RobotState& state) const = 0;
  virtual void write(const JointCommand& command) = 0;
};

/// A controller called by the robot side at a fixed rate (1 kHz). tick() must not allocate nor throw.
class Controller {
 public:
  virtual ~Controller() = default;
  /// Called once before the loop with the first measurement (may allocate).
  virtual void start(const RobotState& state, JointCommand& command) = 0;
  /// Called every control period.
  virtual void tick(const RobotState& state, JointCommand& command) noexcept = 0;
};

/// What a supervising node reports of its controller (no allocation: the strings are static).
struct ControllerReport {
  const char* phase = "";        ///< e.g. "standing", "waiting", "settle", "primitive", "recover", "end"
  bool safe_mode = false;
  const char* safe_reason = "";  ///< "" outside safe mode, else e.g. "invalid_input", "qp_failed", "requested"
  std::array<bool, 4> stance{};  ///< wheels (wheel_1..4) the controller treats as in contact
};

/// A controller that a node can supervise: put into its safe mode from outside (e.g. the robot's state went
/// stale), resumed, started on a trigger, and asked what it is doing. None of these allocate or throw.
class SupervisedController : public Controller {
 public:
  /// Enter the safe mode at the next tick (hold the posture with damping), latched until resume().
  virtual void requestSafeMode() noexcept = 0;
  /// Leave the safe mode at the next tick with a valid input.
  virtual void resume() noexcept = 0;
  virtual ControllerReport report() const noexcept = 0;
  /// Start the timed part (e.g. a jump primitive) at robot time t [s], when the controller waits for a
  /// trigger; controllers without a timeline ignore it.
  virtual void triggerStart(double t) noexcept = 0;
  /// The joints it commands, in the order of RobotState and JointCommand.
  virtual const std::vector<std::string>& jointNames() const = 0;
};

}  // namespace centaur
