#include "stabilizers/no_stabilizer.hpp"

#include "controller/whole_body_controller.hpp"
#include "stabilizers/stabilizer_stacks.hpp"

namespace centaur {

std::string NoStabilizer::stackYaml(const RobotFrames& frames) const { return postureStackYaml(frames); }

void NoStabilizer::start(const std::vector<std::string>&, const Eigen::VectorXd& q_home) {
  q_home_ = q_home;
}

unsigned NoStabilizer::references() const { return WholeBodyReferences::kPosture; }

void NoStabilizer::update(const RobotState&, double, bool, WholeBodyReferences& out) noexcept {
  out.q_posture = q_home_;
  out.set = WholeBodyReferences::kPosture;
}

}  // namespace centaur
