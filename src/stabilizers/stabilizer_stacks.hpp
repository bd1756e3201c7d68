#pragma once
// The IK stacks of the jump stabilizers (YAML text in the format of docs/controller.md), x = v (nv = 45).
//   postureStackYaml():   (sum_i Pelvis->Foot_i [XYZ]) / Posture  << (position limits + velocity limits)
//                         eq. (box_stack_Raibert): used by "none", "raibert" and "ocp" (the posture reference
//                         is what differs).
//   angmomStackYaml():    (sum_i Pelvis->Foot_i) / World->Pelvis / (AngMom + Posture) << (limits)
//                         eq. (box_stack_angular_momentum), the momentum task on the shoulder and elbow joints.
// Feet: base -> foot centre positions (tasks wheel_1..wheel_4), gain 20 1/s. The robot's names come from `frames`
// (CENTAURO's by default: pelvis, wheel_centre_1..4, the shoulder and elbow joints j_arm*_1..4).
#include <string>

#include "controller/robot_frames.hpp"

namespace centaur {

std::string postureStackYaml(const RobotFrames& frames = RobotFrames());
std::string angmomStackYaml(const RobotFrames& frames = RobotFrames());

}  // namespace centaur
