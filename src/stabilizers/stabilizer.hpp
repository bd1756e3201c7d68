#pragma once
// An upper-body stabilizer (paper Sec. IV): every control period it reads the measurement (IMU angular
// velocity, joint state) and returns references (posture, its velocity, pelvis angular velocity, angular
// momentum: WholeBodyReferences), which the jump controller hands the whole-body controller; references() says
// which it may return, and the jump controller checks that its stack has their tasks. Each stabilizer needs its own IK stack
// (which tasks exist, at which priority): stackYaml() returns it, and the jump controller builds the
// WholeBodyController from it.
//
// Frames: RobotState::imu_omega is the IMU's angular velocity in the IMU frame (the IMU is fixed to the
// pelvis with the pelvis axes, so x = roll, y = pitch, z = yaw rates of the pelvis); imu_quat is w_R_imu.
//
// Life cycle: configure (constructor, may throw InputError) -> start() once with the robot's joint names and
// home posture (may allocate) -> update() every period (never allocates, never throws).
#include <string>
#include <vector>

#include <Eigen/Core>

#include "controller/robot_interface.hpp"
#include "controller/whole_body_controller.hpp"

namespace centaur {

class Stabilizer {
 public:
  virtual ~Stabilizer() = default;
  /// "none", "raibert", "angmom", "ocp".
  virtual const char* name() const = 0;
  /// The IK stack this stabilizer runs with on the robot of `frames` (YAML text in the format of docs/controller.md).
  virtual std::string stackYaml(const RobotFrames& frames) const = 0;
  /// Once, before the loop: joint names (RobotModel order) and the home posture [rad] (n).
  virtual void start(const std::vector<std::string>& joint_names, const Eigen::VectorXd& q_home) = 0;
  /// The WholeBodyReferences bits update() may set.
  virtual unsigned references() const = 0;
  /// Every control period (dt [s]); `active` is false before the primitive starts and after it ended
  /// (a stabilizer may keep acting or relax towards home then). Fills `out` (sized by the caller, n joints) and
  /// sets out.set to the references it carries this period.
  virtual void update(const RobotState& state, double dt, bool active, WholeBodyReferences& out) noexcept = 0;
};

}  // namespace centaur
