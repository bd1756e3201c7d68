#pragma once
// CoM task (world frame): A = J_com (3 x nv), b = com_d - com (+ comdot_ff / lambda).
// With x = v the base linear velocity moves the CoM one to one: the task constrains the joints only when a
// higher level fixes the base (e.g. Cartesian tasks with base_link "world" on the stance wheels).
// update() never allocates nor throws.
#include "model/robot_model.hpp"
#include "qp/task.hpp"

namespace centaur {

class ComTask : public Task {
 public:
  ComTask(std::string name, const RobotModel& model);
  void setReference(const Eigen::Vector3d& w_com_d) { com_d_ = w_com_d; }
  void setVelocityReference(const Eigen::Vector3d& comdot_ff) { comdot_ff_ = comdot_ff; }
  /// Reference := current CoM.
  void holdCurrent() { com_d_ = model_.com(); }
  const Eigen::Vector3d& reference() const { return com_d_; }
  void update() override;

 private:
  const RobotModel& model_;
  RowMatrixXd J_;
  Eigen::Vector3d com_d_ = Eigen::Vector3d::Zero(), comdot_ff_ = Eigen::Vector3d::Zero();
};

}  // namespace centaur
