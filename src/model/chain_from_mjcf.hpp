#pragma once
// Extract a fixed-base serial chain (model/serial_chain.hpp) from an MJCF file, at its "home" keyframe.
// MuJoCo is used privately (as in robot_model.cpp); no MuJoCo type appears here.
//
// What is read, per joint (MJCF names): the link body's pos/quat in its parent (parent_p, parent_R), the hinge
// axis, the body's inertial merged with every descendant body that has no joint (welded: e.g. the arm's
// force-torque sensor and ball hand), dof_armature, jnt_range, the velocity limit from the joint's first user
// value (as RobotModel), the effort limit from the joint's motor (|gear| * max |ctrlrange|), the home value.
// The base body's pose in the reference body, and gravity, are taken at the home keyframe.
// Requirements (InputError naming the file and joint otherwise): every joint is a hinge with its anchor at the
// body origin, each link body carries exactly that one joint, link i's body is the parent of link i+1's, and
// the first link's parent is `base_body`.
#include <string>
#include <vector>

#include "model/serial_chain.hpp"

namespace centaur::model {

struct ChainSpec {
  std::string reference_body = "pelvis";  ///< frame R of every result
  std::string base_body = "torso_2";      ///< held fixed at its home pose
  std::vector<std::string> joints;        ///< in order from the base
  std::string ee_frame = "ball1_tip";     ///< a site or body on (or welded to) the last link
};

/// The left CENTAURO arm: j_arm1_1..j_arm1_7 on torso_2, end-effector the hand tip site ball1_tip.
ChainSpec centauroLeftArmSpec();

/// Throws InputError (file, joint, reason) for a missing file or a chain that does not meet the requirements.
SerialChain chainFromMjcf(const std::string& mjcf_path, const ChainSpec& spec);

/// The MJCF shipped with the repository: <CENTAUR_SOURCE_DIR>/models/centauro/centauro.xml.
std::string centauroMjcfPath();

}  // namespace centaur::model
