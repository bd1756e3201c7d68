#pragma once
// What the online stage must know of a robot beyond its MJCF: the names of its base, IMU, feet and wheel joints,
// where each foot's centre sits on its contact body, and which joints form each impedance group. The caller fills
// it from the robot's description (robot/robot_description.hpp, robot.yaml); the online stage never reads
// robot.yaml itself. The defaults are CENTAURO's (models/centauro/robot.yaml), for callers that pass no robot.
#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

namespace centaur {

/// An impedance group: the joints whose names match one of the fnmatch(3) patterns (the first group wins).
struct GainPattern {
  std::string group;
  std::vector<std::string> patterns;
};

struct RobotFrames {
  std::string base = "pelvis";  ///< the floating base's body
  std::string imu = "imu";      ///< the IMU's site (axes of the measured angular velocity)
  /// Foot order FL, FR, RL, RR: the body that touches the ground and the site at the foot's centre.
  std::array<std::string, 4> contact_bodies = {"wheel_1", "wheel_2", "wheel_3", "wheel_4"};
  std::array<std::string, 4> foot_centres = {"wheel_centre_1", "wheel_centre_2", "wheel_centre_3", "wheel_centre_4"};
  /// [m] each foot's centre in its contact body's frame (zero: at the body's origin, exactly).
  std::array<Eigen::Vector3d, 4> centre_offsets = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                                                   Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  /// Each leg's joints, root to foot (the contact detector's rows of each leg).
  std::array<std::vector<std::string>, 4> leg_joints = {
      std::vector<std::string>{"hip_yaw_1", "hip_pitch_1", "knee_pitch_1", "ankle_pitch_1", "ankle_yaw_1", "j_wheel_1"},
      std::vector<std::string>{"hip_yaw_2", "hip_pitch_2", "knee_pitch_2", "ankle_pitch_2", "ankle_yaw_2", "j_wheel_2"},
      std::vector<std::string>{"hip_yaw_3", "hip_pitch_3", "knee_pitch_3", "ankle_pitch_3", "ankle_yaw_3", "j_wheel_3"},
      std::vector<std::string>{"hip_yaw_4", "hip_pitch_4", "knee_pitch_4", "ankle_pitch_4", "ankle_yaw_4", "j_wheel_4"}};
  /// [m] each foot's radius: its contact point lies this far below its centre, along the surface normal.
  std::array<double, 4> foot_radius = {0.078, 0.078, 0.078, 0.078};
  /// Rolling joints, which hold their initial angle when standing. Empty: every joint whose name has "wheel".
  std::vector<std::string> wheel_joints;
  /// Impedance groups. Empty: CENTAURO's groups by name (controller/standing_controller.cpp, gainsFor).
  std::vector<GainPattern> gain_patterns;
  /// The joints the angular-momentum stabilizer's momentum task moves (robot.yaml stabilizers.angmom).
  std::vector<std::string> angmom_joints = {"j_arm1_1", "j_arm1_2", "j_arm1_3", "j_arm1_4",
                                            "j_arm2_1", "j_arm2_2", "j_arm2_3", "j_arm2_4"};
};

}  // namespace centaur
