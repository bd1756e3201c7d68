#include "controller/model_joint_limits.hpp"

namespace centaur {

ModelJointPositionLimits::ModelJointPositionLimits(std::string name, const RobotModel& model, double dt,
                                                   double scaling)
    : JointPositionLimits(std::move(name), model.nv(), 6, model.limits().q_min, model.limits().q_max, dt, scaling),
      model_(model) {
  q_ = model.homeJoints();
}

void ModelJointPositionLimits::update() {
  q_ = model_.q().tail(model_.numJoints());
  JointPositionLimits::update();
}

}  // namespace centaur
