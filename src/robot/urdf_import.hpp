#pragma once
// `centaur model import ROBOT.urdf --out DIR`: a URDF turned into centaur's robot input, an MJCF of the robot
// alone (DIR/<name>.xml) plus the skeleton of its semantic layer (DIR/robot.yaml, robot/robot_description.hpp).
//
// MuJoCo's own URDF compiler does the conversion (mj_loadXML on the URDF, mj_saveLastXML); before it, the URDF
// text loses the meshes that cannot be found and gains the MuJoCo compiler options that keep fixed links as
// bodies. The saved MJCF then gets what centaur needs and a URDF cannot say: a free joint on the base, torque
// motors from the effort limits, joint velocity limits in the joint `user` field, the IMU site and sensors, a site
// on each foot's contact body and each arm's tip, and a `home` keyframe at the zero posture with the feet on the
// ground. Everything robot.yaml says about the robot's structure (feet, arms, stabilizer joints, gains) is
// guessed from the kinematic tree and marked `# GUESS` for the user to confirm.
//
// The same URDF gives the same bytes. Nothing is written on bad input.
#include <array>
#include <map>
#include <string>
#include <vector>

struct mjModel_;

namespace centaur::robot {

struct UrdfImportReport {
  std::string mjcf_path, yaml_path;   ///< files written in DIR: <name>.xml and robot.yaml
  std::string name;                   ///< the URDF robot name, sanitized to [a-z0-9_-]
  int hinge_joints = 0;               ///< actuated joints of the result (one motor each)
  double total_mass = 0.0;            ///< [kg]
  std::vector<std::string> warnings;  ///< e.g. "link 'pelvis': mesh 'package://x/y.stl' not found, dropped"
};

/// Converts `urdf_path` with MuJoCo's own URDF compiler (mj_loadXML on the URDF, then mj_saveLastXML) into
/// DIR/<name>.xml + DIR/robot.yaml (DIR is created if missing). Throws centaur::InputError (common/error.hpp)
/// naming the file for bad input: a missing file, not a URDF, MuJoCo refuses it, no links (besides `world`), a
/// joint type other than revolute/continuous/fixed/floating, more than one floating joint, a base attached to the
/// world by a hinge. Nothing is written then (the pre-processed URDF never touches the disk: MuJoCo reads it from
/// a virtual file system; MuJoCo's saved MJCF passes through a temporary in /tmp that is removed at once). RuntimeError for a failure of the machine (I/O, MuJoCo cannot save).
UrdfImportReport importUrdf(const std::string& urdf_path, const std::string& out_dir);

/// The name of a robot as centaur records it: lower case, every character outside [a-z0-9_-] replaced by '_',
/// at most 64 characters; "robot" if nothing is left.
std::string sanitizeRobotName(const std::string& urdf_name);

namespace detail {
// Shared by urdf_import.cpp (URDF, MuJoCo, MJCF) and urdf_import_yaml.cpp (structure guess, robot.yaml).

/// What the URDF says about one joint that the compiled MJCF does not keep.
struct UrdfJoint {
  std::string type;       ///< revolute, continuous, fixed or floating
  double effort = 0.0;    ///< [N m] <limit effort>; 0 = none given
  double velocity = 0.0;  ///< [rad/s] <limit velocity>; 0 = none given
};
using UrdfJoints = std::map<std::string, UrdfJoint>;

struct FootGuess {
  std::string root, contact, centre, wheel_joint;  ///< bodies, the centre site, the rolling joint ("" = none)
  bool wheel = false;                              ///< type wheel (else point)
  std::array<double, 3> centre_pos{};              ///< centre site in the contact body's frame [m]
  double centre_z = 0.0;                           ///< centre site height in the base frame, zero posture [m]
  double radius = 0.0;                             ///< radius of the contact body's collision geom, 0 = none [m]
  std::vector<std::string> joints;                 ///< hinges of the leg, root to tip
};

struct ArmGuess {
  std::string name, tip_body, tip_site, mirrors;
  std::vector<std::string> joints;  ///< hinges, root to tip
};

/// The robot's structure as guessed from the compiled URDF's kinematic tree at the zero posture.
struct RobotGuess {
  std::string base;                  ///< the root body (gets the free joint)
  std::string imu_body;              ///< body carrying the `imu` site
  bool feet_found = false;           ///< four legs found; `feet` in FL, FR, RL, RR order
  std::array<FootGuess, 4> feet;
  std::vector<ArmGuess> arms;        ///< 0..2, left first
  std::vector<std::string> torso_joints, stabilizer_joints;
  double home_height = 0.0;          ///< base height of the home keyframe [m]
};

/// Guesses feet, arms, IMU body and home height from `m` (the URDF as MuJoCo compiled it); appends warnings.
RobotGuess guessStructure(const mjModel_* m, const UrdfJoints& joints, std::vector<std::string>& warnings);

/// robot.yaml for the robot `name` whose MJCF is the file `mjcf_file` (relative to robot.yaml), from `guess`.
std::string robotYaml(const std::string& name, const std::string& mjcf_file, const std::string& urdf_file,
                      const RobotGuess& guess);

}  // namespace detail

}  // namespace centaur::robot
