#include "stabilizers/no_stabilizer.hpp"

#include "controller/whole_body_controller.hpp"
#include "stabilizers/stabilizer_stacks.hpp"

namespace centaur {

std::string NoStabilizer::stackYaml() const { return postureStackYaml(); }

void NoStabilizer::start(const std::vector<std::string>&, const Eigen::VectorXd& q_home) {
  q_home_ = q_home;
  sent_ = false;
}

void NoStabilizer::update(const RobotState&, double, bool, WholeBodyController& wbc) noexcept {
  if (!sent_) wbc.setPostureReference(q_home_);
  sent_ = true;
}

}  // namespace centaur
