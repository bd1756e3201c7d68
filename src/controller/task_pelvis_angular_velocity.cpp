#include "controller/task_pelvis_angular_velocity.hpp"

#include <stdexcept>

namespace centaur {

PelvisAngularVelocityTask::PelvisAngularVelocityTask(std::string name, const RobotModel& model,
                                                     const std::string& base)
    : Task(std::move(name), 3, model.nv()), model_(model), base_(model.frameId(base)) {
  if (base_ < 0) throw std::invalid_argument("PelvisAngularVelocity task '" + name_ + "': unknown frame " + base);
  J_.setZero(6, model.nv());
}

void PelvisAngularVelocityTask::update() {
  model_.frameJacobian(base_, J_);
  A_ = J_.bottomRows<3>();
  const Eigen::Matrix3d w_R_b = model_.framePose(base_).linear();
  b_ = omega_d_;
  if (k_ > 0.0 && lambda_ > 0.0) {
    const Eigen::AngleAxisd aa(R_ref_ * w_R_b.transpose());
    b_ += (k_ / lambda_) * aa.angle() * aa.axis();
  }
}

}  // namespace centaur
