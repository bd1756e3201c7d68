#include "controller/task_com.hpp"

namespace centaur {

ComTask::ComTask(std::string name, const RobotModel& model) : Task(std::move(name), 3, model.nv()), model_(model) {
  J_.setZero(3, model.nv());
}

void ComTask::update() {
  model_.comJacobian(J_);
  A_ = J_;
  b_.head<3>() = com_d_ - model_.com();
  if (lambda_ > 0.0) b_.head<3>() += comdot_ff_ / lambda_;
}

}  // namespace centaur
