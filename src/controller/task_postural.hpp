#pragma once
// Postural task: a subset of the actuated joints towards a reference q_d (x = v: joint i is column 6 + i).
//   A = selection rows,  b = q_d - q  (+ qd_ff / lambda),  q = the model's joint positions (last update()).
// Continuous joints (wheels) are treated like the others (the reference is an angle, e.g. the initial one).
// update() never allocates nor throws.
#include <vector>

#include "model/robot_model.hpp"
#include "qp/task.hpp"

namespace centaur {

class PosturalTask : public Task {
 public:
  /// joints: indices into RobotModel's actuated joints (all if empty); the reference starts at home.
  PosturalTask(std::string name, const RobotModel& model, std::vector<int> joints = {});
  /// Reference of ALL n actuated joints (only the task's are used) [rad].
  void setReference(const Eigen::Ref<const Eigen::VectorXd>& q_d) { q_d_ = q_d; }
  /// Velocity feed-forward of all n joints [rad/s].
  void setVelocityReference(const Eigen::Ref<const Eigen::VectorXd>& qd_ff) { qd_ff_ = qd_ff; }
  const Eigen::VectorXd& reference() const { return q_d_; }
  const std::vector<int>& joints() const { return joints_; }
  void update() override;

 private:
  const RobotModel& model_;
  std::vector<int> joints_;
  Eigen::VectorXd q_d_, qd_ff_;
};

}  // namespace centaur
