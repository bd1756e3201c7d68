#pragma once
// Cartesian task on RobotModel (velocity IK, decision variable x = v, nv = 6 + n; see docs/controller.md):
// the pose of a distal frame relative to a base frame, expressed in the BASE frame (the paper's first
// level: pelvis -> wheel_k). Rows: 3 position rows, plus 3 orientation rows if `orientation` is true.
//
//   position     r = b_R_w (w_p_distal - w_p_base);  rdot = b_R_w (J_distal,lin - J_base,lin) v  (joint columns:
//                the relative pose does not depend on the base twist, so the 6 base columns are exactly zero)
//   orientation  b_omega_rel = b_R_w (J_distal,ang - J_base,ang) v, error log(b_R_ref b_R_distal^T) (base frame)
//   b = [r_ref - r; log(R_ref R^T)] + v_ff / lambda   (v_ff: optional velocity feed-forward, base frame)
//
// base_link "world": the distal frame's absolute pose in the world frame (A = J_distal, with base columns;
// use it for wheels fixed on the ground when the base twist must follow from the contacts).
// update() reads the model's last update(); no allocation, no throw.
#include <Eigen/Geometry>

#include "model/robot_model.hpp"
#include "qp/task.hpp"

namespace centaur {

class CartesianTask : public Task {
 public:
  /// base: frame name or "world"; throws std::invalid_argument for an unknown frame. The reference starts at
  /// the current relative pose (call holdCurrent() after the model has been updated).
  CartesianTask(std::string name, const RobotModel& model, const std::string& base, const std::string& distal,
                bool orientation);

  /// Reference pose of the distal frame in the base frame (or world).
  void setReference(const Eigen::Vector3d& p_ref, const Eigen::Matrix3d& R_ref = Eigen::Matrix3d::Identity());
  /// Velocity feed-forward [linear; angular] (base frame or world), rows() entries used.
  void setVelocityReference(const Eigen::Matrix<double, 6, 1>& v_ff) { v_ff_ = v_ff; }
  /// Reference := the current relative pose (model's last update()), feed-forward := 0.
  void holdCurrent();
  /// Current relative pose (model's last update()).
  void currentPose(Eigen::Vector3d& p, Eigen::Matrix3d& R) const;

  const Eigen::Vector3d& positionReference() const { return p_ref_; }
  /// ||r_ref - r|| at the model's last update() [m].
  double positionError() const;
  bool world() const { return base_ < 0; }
  void update() override;

 private:
  const RobotModel& model_;
  int base_ = -1, distal_ = -1;
  bool orientation_ = false;
  RowMatrixXd Jb_, Jd_;
  Eigen::Vector3d p_ref_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3d R_ref_ = Eigen::Matrix3d::Identity();
  Eigen::Matrix<double, 6, 1> v_ff_ = Eigen::Matrix<double, 6, 1>::Zero();
};

}  // namespace centaur
