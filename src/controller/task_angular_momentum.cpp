#include "controller/task_angular_momentum.hpp"

namespace centaur {

AngularMomentumTask::AngularMomentumTask(std::string name, const RobotModel& model)
    : Task(std::move(name), 3, model.nv()), model_(model) {
  Ag_.setZero(6, model.nv());
}

void AngularMomentumTask::update() {
  model_.centroidalMomentumMatrix(Ag_);
  A_ = Ag_.bottomRows<3>();
  b_ = lambda_ > 0.0 ? Eigen::Vector3d(h_d_ / lambda_) : Eigen::Vector3d::Zero();
}

}  // namespace centaur
