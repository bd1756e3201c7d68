#include "controller/task_cartesian.hpp"

#include <stdexcept>

namespace centaur {

CartesianTask::CartesianTask(std::string name, const RobotModel& model, const std::string& base,
                             const std::string& distal, bool orientation)
    : Task(std::move(name), orientation ? 6 : 3, model.nv()), model_(model), orientation_(orientation) {
  base_ = base == "world" ? -1 : model.frameId(base);
  distal_ = model.frameId(distal);
  if (base != "world" && base_ < 0) throw std::invalid_argument("Cartesian task '" + name_ + "': unknown frame " + base);
  if (distal_ < 0) throw std::invalid_argument("Cartesian task '" + name_ + "': unknown frame " + distal);
  Jb_.setZero(6, model.nv());
  Jd_.setZero(6, model.nv());
}

void CartesianTask::setReference(const Eigen::Vector3d& p_ref, const Eigen::Matrix3d& R_ref) {
  p_ref_ = p_ref;
  R_ref_ = R_ref;
}

void CartesianTask::currentPose(Eigen::Vector3d& p, Eigen::Matrix3d& R) const {
  const Eigen::Isometry3d w_T_d = model_.framePose(distal_);
  if (base_ < 0) {
    p = w_T_d.translation();
    R = w_T_d.linear();
    return;
  }
  const Eigen::Isometry3d w_T_b = model_.framePose(base_);
  p.noalias() = w_T_b.linear().transpose() * (w_T_d.translation() - w_T_b.translation());
  R.noalias() = w_T_b.linear().transpose() * w_T_d.linear();
}

void CartesianTask::holdCurrent() {
  currentPose(p_ref_, R_ref_);
  v_ff_.setZero();
}

double CartesianTask::positionError() const {
  Eigen::Vector3d p;
  Eigen::Matrix3d R;
  currentPose(p, R);
  return (p_ref_ - p).norm();
}

void CartesianTask::update() {
  const int nv = model_.nv();
  model_.frameJacobian(distal_, Jd_);
  Eigen::Vector3d p;
  Eigen::Matrix3d R;
  currentPose(p, R);
  if (base_ < 0) {
    A_ = Jd_.topRows(rows());
  } else {
    model_.frameJacobian(base_, Jb_);
    const Eigen::Matrix3d b_R_w = model_.framePose(base_).linear().transpose();
    Jd_ -= Jb_;
    A_.leftCols<6>().setZero();
    A_.block<3, Eigen::Dynamic>(0, 6, 3, nv - 6).noalias() = b_R_w * Jd_.block<3, Eigen::Dynamic>(0, 6, 3, nv - 6);
    if (orientation_)
      A_.block<3, Eigen::Dynamic>(3, 6, 3, nv - 6).noalias() = b_R_w * Jd_.block<3, Eigen::Dynamic>(3, 6, 3, nv - 6);
  }
  b_.head<3>() = p_ref_ - p;
  if (orientation_) {
    const Eigen::AngleAxisd aa(R_ref_ * R.transpose());
    b_.tail<3>() = aa.angle() * aa.axis();
  }
  if (lambda_ > 0.0) b_ += v_ff_.head(rows()) / lambda_;
}

}  // namespace centaur
