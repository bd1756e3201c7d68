#pragma once
// Mode "none": no upper-body stabilization. The stack of eq. (box_stack_Raibert) with the posture held at home
// (the baseline of the paper's comparison).
#include "stabilizers/stabilizer.hpp"

namespace centaur {

class NoStabilizer final : public Stabilizer {
 public:
  const char* name() const override { return "none"; }
  std::string stackYaml(const RobotFrames& frames) const override;
  void start(const std::vector<std::string>& joint_names, const Eigen::VectorXd& q_home) override;
  unsigned references() const override;
  void update(const RobotState& state, double dt, bool active, WholeBodyReferences& out) noexcept override;

 private:
  Eigen::VectorXd q_home_;
};

}  // namespace centaur
