#include "controller/task_angular_momentum.hpp"

#include <algorithm>

namespace centaur {

AngularMomentumTask::AngularMomentumTask(std::string name, const RobotModel& model, std::vector<int> joints)
    : Task(std::move(name), 3, model.nv()), model_(model) {
  Ag_.setZero(6, model.nv());
  if (!joints.empty()) {
    for (int i = 0; i < model.numJoints(); ++i) {
      if (std::find(joints.begin(), joints.end(), i) == joints.end()) zeroed_.push_back(i);
    }
  }
}

void AngularMomentumTask::update() {
  model_.centroidalMomentumMatrix(Ag_);
  A_ = Ag_.bottomRows<3>();
  for (int i : zeroed_) A_.col(6 + i).setZero();
  if (lambda_ > 0.0) {
    b_.head<3>() = h_d_ / lambda_;
  } else {
    b_.head<3>().setZero();
  }
}

}  // namespace centaur
