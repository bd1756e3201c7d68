#pragma once
// Pelvis (base) angular velocity in the WORLD frame (the paper's second level): with x = v and
// v = [w_v_base, b_omega_base, qd], w_omega = J_ang v (the frame's world-aligned angular Jacobian rows; for the
// free-joint body: A = [0_3  w_R_base  0], 3 x nv) and
// b = omega_d (world frame; lambda should stay 1 so that A x = omega_d). Optionally, an orientation reference
// adds feedback: b = omega_d + (k / lambda) log(w_R_ref w_R_base^T) (k = orientation_gain [1/s], 0 = off).
// update() reads the model's last update(); no allocation, no throw.
#include <Eigen/Geometry>

#include "model/robot_model.hpp"
#include "qp/task.hpp"

namespace centaur {

class PelvisAngularVelocityTask : public Task {
 public:
  /// base: the floating-base frame (e.g. "pelvis"); throws std::invalid_argument if unknown.
  PelvisAngularVelocityTask(std::string name, const RobotModel& model, const std::string& base = "pelvis");
  /// omega_fb,d (W) [rad/s].
  void setReference(const Eigen::Vector3d& w_omega_d) { omega_d_ = w_omega_d; }
  const Eigen::Vector3d& reference() const { return omega_d_; }
  /// Orientation feedback: w_R_ref and gain k >= 0 [1/s].
  void setOrientationReference(const Eigen::Matrix3d& w_R_ref, double gain) {
    R_ref_ = w_R_ref;
    k_ = gain;
  }
  void update() override;

 private:
  const RobotModel& model_;
  int base_ = -1;
  Eigen::Vector3d omega_d_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3d R_ref_ = Eigen::Matrix3d::Identity();
  double k_ = 0.0;
  RowMatrixXd J_;
};

}  // namespace centaur
