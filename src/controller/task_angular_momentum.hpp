#pragma once
// Centroidal angular momentum task: the angular rows (3..5) of the centroidal momentum matrix,
//   A = A_G,ang(q) (3 x nv, about the CoM, world frame),  b = h_ang,d / lambda  (lambda 1 by default, so
// A x = h_ang,d) [kg m^2/s]. With x = v, the base linear velocity does not enter (a translation has no
// angular momentum about the CoM). Optional joint subset: only the base columns and the listed joints' columns
// are kept (the others are zeroed, so those joints are left to the other tasks; e.g. the paper engages only
// the shoulder and elbow joints). update() never allocates nor throws.
#include <vector>

#include "model/robot_model.hpp"
#include "qp/task.hpp"

namespace centaur {

class AngularMomentumTask : public Task {
 public:
  /// joints: indices into the actuated joints whose columns are kept (all if empty).
  AngularMomentumTask(std::string name, const RobotModel& model, std::vector<int> joints = {});
  void setReference(const Eigen::Vector3d& h_ang_d) { h_d_ = h_ang_d; }
  const Eigen::Vector3d& reference() const { return h_d_; }
  void update() override;

 private:
  const RobotModel& model_;
  RowMatrixXd Ag_;
  std::vector<int> zeroed_;  // actuated joints whose columns are zeroed
  Eigen::Vector3d h_d_ = Eigen::Vector3d::Zero();
};

}  // namespace centaur
