#include "stabilizers/stabilizer_stacks.hpp"

namespace centaur {

namespace {
const char* const kFeet = R"(
wheel_1: {type: Cartesian, base_link: pelvis, distal_link: wheel_centre_1, lambda: 20.0}
wheel_2: {type: Cartesian, base_link: pelvis, distal_link: wheel_centre_2, lambda: 20.0}
wheel_3: {type: Cartesian, base_link: pelvis, distal_link: wheel_centre_3, lambda: 20.0}
wheel_4: {type: Cartesian, base_link: pelvis, distal_link: wheel_centre_4, lambda: 20.0}
joint_limits: {type: JointPositionLimits, scaling: 0.5}
velocity_limits: {type: JointVelocityLimits, scaling: 1.0}
regularisation: 1.0e-6
constraints: [joint_limits, velocity_limits]
)";
}  // namespace

std::string postureStackYaml() {
  return std::string(R"(stack:
  - [wheel_1, wheel_2, wheel_3, wheel_4]
  - [posture]
posture: {type: Postural, lambda: 10.0})") + kFeet;
}

std::string angmomStackYaml() {
  return std::string(R"(stack:
  - [wheel_1, wheel_2, wheel_3, wheel_4]
  - [pelvis]
  - [ang_mom, posture]
pelvis: {type: PelvisAngularVelocity, base_link: pelvis}
ang_mom:
  type: AngularMomentum
  indices: [1]                   # pitch row only (the tilting axis)
  weight: 1.0
  joints: [j_arm1_1, j_arm1_2, j_arm1_3, j_arm1_4, j_arm2_1, j_arm2_2, j_arm2_3, j_arm2_4]
posture: {type: Postural, lambda: 10.0, weight: 0.01})") + kFeet;
}

}  // namespace centaur
