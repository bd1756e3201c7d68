#pragma once
// JointPositionLimits that reads the joint positions from the RobotModel's last update() (x = v: the joints
// are columns 6.. of x), so the controller never has to feed q by hand. update() never allocates nor throws.
#include "model/robot_model.hpp"
#include "qp/constraint.hpp"

namespace centaur {

class ModelJointPositionLimits : public JointPositionLimits {
 public:
  /// Bounds from model.limits(); dt [s] the IK period; scaling in (0, 1].
  ModelJointPositionLimits(std::string name, const RobotModel& model, double dt, double scaling = 1.0);
  void update() override;

 private:
  const RobotModel& model_;
};

}  // namespace centaur
