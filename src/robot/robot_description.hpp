#pragma once
// A robot as centaur's input: an MJCF of the robot alone plus `robot.yaml`, the semantic layer (in the style
// of an SRDF) that names what the MJCF cannot say: the base, the IMU and its sensors, the home keyframe, the
// four feet in template order, the torso and arm joints, the stabilizers' joints, the joint impedance gains
// by joint-name pattern and optional joint-limit overrides. Schema, defaults and ranges: docs/robots.md.
//
// This is the one place that reads `robot.yaml` (strictly: unknown keys, missing keys, ranges and names are
// errors naming the file and the key). What can be derived from the MJCF is not in this file but in
// robot/robot_facts.hpp, computed once from it.
#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace centaur::robot {

/// The template's foot order, the order of RobotDescription::feet.
inline constexpr std::array<const char*, 4> kFootNames = {"FL", "FR", "RL", "RR"};
/// At most this many arms, each with at most kMaxArmJoints joints.
inline constexpr int kMaxArms = 2;
inline constexpr int kMaxArmJoints = 8;

enum class FootType { kWheel, kPoint };
const char* footTypeName(FootType t);

struct FootSpec {
  std::string name;         ///< FL, FR, RL or RR
  std::string root;         ///< body where the leg leaves the trunk (its subtree is the leg)
  std::string contact;      ///< body that touches the ground (the wheel, or the lower leg of a point foot)
  std::string centre;       ///< site at the foot centre (wheel centre, centre of a point foot's sphere)
  FootType type = FootType::kWheel;
  std::string wheel_joint;  ///< wheels: the rolling joint ("" = none)
  double radius = 0.0;      ///< [m] contact point below the centre; 0 = `auto` (from the contact geom)
};

struct ArmSpec {
  std::string name;
  std::vector<std::string> joints;  ///< root to tip, 1..kMaxArmJoints hinges
  std::string end_effector;         ///< site or body at the tip
  std::string mirrors;              ///< name of the arm this one is the sagittal mirror image of ("" = none)
};

struct GainGroup {
  std::string group;                  ///< name (what configurations override: controller.gains.<group>)
  std::vector<std::string> patterns;  ///< fnmatch(3) patterns on joint names
  double kp = 0.0;                    ///< [Nm/rad] [0, 1e5]
  double kd = 0.0;                    ///< [Nm s/rad] [0, 1e3]
};

/// A joint's limits as robot.yaml overrides them; NaN = the MJCF's value.
struct LimitOverride {
  std::string joint;
  double q_min = std::numeric_limits<double>::quiet_NaN();    ///< [rad]
  double q_max = std::numeric_limits<double>::quiet_NaN();    ///< [rad]
  double qd_max = std::numeric_limits<double>::quiet_NaN();   ///< [rad/s]
  double tau_max = std::numeric_limits<double>::quiet_NaN();  ///< [Nm]
};

struct ImuSpec {
  std::string site, orientation, gyro, accelerometer;  ///< the site and its framequat, gyro, accelerometer sensors
};

struct RobotDescription {
  std::string name;       ///< [a-z0-9_-]{1,64}, recorded in primitives and logs
  std::string yaml_path;  ///< the robot.yaml read
  std::string mjcf_path;  ///< absolute or relative to the working directory (resolved from robot.yaml's folder)
  std::string base;       ///< body with the free joint
  std::string home;       ///< keyframe of the home posture
  bool scene_in_mjcf = false;  ///< key `scene`: `mjcf` = the MJCF carries its own ground and wall (CENTAURO's
                               ///< paper-era file); `centaur` (default) = it is the robot alone, centaur adds them
  ImuSpec imu;
  std::array<FootSpec, 4> feet;  ///< FL, FR, RL, RR
  std::vector<std::string> torso_joints;
  std::vector<ArmSpec> arms;     ///< 0..kMaxArms
  std::vector<std::string> raibert_joints, angmom_joints;
  std::vector<GainGroup> gains;  ///< in order: the first matching group wins
  std::vector<LimitOverride> limits;
  std::string hash;  ///< 16 hex digits: FNV-1a 64 of robot.yaml's bytes, then the MJCF's

  /// The first gain group whose pattern matches `joint`, or nullptr.
  const GainGroup* gainsFor(const std::string& joint) const;
  /// Index of the arm called `name`, -1 if none.
  int armIndex(const std::string& name) const;
};

/// Reads `path` (a robot.yaml, or a folder holding one). Throws InputError naming the file and key for a missing
/// file, an unknown or missing key, a value out of range or of the wrong kind; never touches the MJCF beyond
/// hashing its bytes (names are checked against the MJCF by checkRobot(), robot/robot_check.hpp).
RobotDescription readRobotDescription(const std::string& path);

/// FNV-1a 64 of `bytes`, continuing from `h` (the offset basis by default).
std::uint64_t fnv1a64(const std::string& bytes, std::uint64_t h = 14695981039346656037ull);

}  // namespace centaur::robot
