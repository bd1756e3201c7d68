#pragma once
// The only door between the controller and a robot (simulated or real).
// The controller reads a RobotState and writes a JointCommand; the robot side runs the joint impedance law
//   tau = tau_ff + kp (q_ref - q) + kd (qd_ref - qd),  saturated at the joint effort limits,
// at its own rate (2 kHz in simulation). Joint order: the robot model's actuated-joint order
// (RobotModel::jointNames()). Nothing here knows about any simulator.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace centaur {

/// What the robot measures. Sized once (resize(n)); never reallocated in the loop.
struct RobotState {
  double t = 0.0;                  ///< [s] robot time
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

}  // namespace centaur
