#include "stabilizers/stabilizer_stacks.hpp"

namespace centaur {

namespace {
// The feet (base -> foot centre, lambda 20 1/s), the limits and the regularisation, common to both stacks.
std::string feetAndLimits(const RobotFrames& f) {
  std::string s = "\n";
  for (int k = 0; k < 4; ++k) {
    s += "wheel_" + std::to_string(k + 1) + ": {type: Cartesian, base_link: " + f.base +
         ", distal_link: " + f.foot_centres[k] + ", lambda: 20.0}\n";
  }
  return s + R"(joint_limits: {type: JointPositionLimits, scaling: 0.5}
velocity_limits: {type: JointVelocityLimits, scaling: 1.0}
regularisation: 1.0e-6
constraints: [joint_limits, velocity_limits]
)";
}
}  // namespace

std::string postureStackYaml(const RobotFrames& frames) {
  return std::string(R"(stack:
  - [wheel_1, wheel_2, wheel_3, wheel_4]
  - [posture]
posture: {type: Postural, lambda: 10.0})") + feetAndLimits(frames);
}

std::string angmomStackYaml(const RobotFrames& frames) {
  std::string joints;
  for (const auto& j : frames.angmom_joints) joints += (joints.empty() ? "" : ", ") + j;
  return std::string(R"(stack:
  - [wheel_1, wheel_2, wheel_3, wheel_4]
  - [pelvis]
  - [ang_mom, posture]
pelvis: {type: PelvisAngularVelocity, base_link: )") + frames.base + R"(}
ang_mom:
  type: AngularMomentum
  indices: [1]                   # pitch row only (the tilting axis)
  weight: 1.0
  joints: [)" + joints + R"(]
posture: {type: Postural, lambda: 10.0, weight: 0.01})" + feetAndLimits(frames);
}

}  // namespace centaur
