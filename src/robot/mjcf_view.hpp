#pragma once
// Internal to the robot module: a loaded MJCF seen through a robot description (ids of what robot.yaml names,
// the legs' subtrees, the home pose with the base at the origin), shared by the checks and the derivation.
// Names no MuJoCo type but the opaque mjModel_/mjData_ pointers.
#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

#include "robot/robot_facts.hpp"

struct mjModel_;
struct mjData_;

namespace centaur::robot::detail {

struct MjcfView {
  const mjModel_* m = nullptr;
  mjData_* d = nullptr;  ///< kinematics at home, base at the origin and upright (B = W)
  int base = -1, home_key = -1, imu_site = -1;
  std::array<int, 4> root{}, contact{}, centre{}, wheel_joint{};  ///< ids (-1: none)
  std::array<double, 4> radius{};                                 ///< [m] resolved (auto -> contact geom)
  std::vector<std::vector<int>> arm_joints;                       ///< joint ids per arm
  std::vector<int> arm_tip_body;                                  ///< body of each arm's end effector
  std::vector<int> leg_of_body;                                   ///< per body: foot index 0-3, or -1
};

/// Whether body `b` is `ancestor` or in its subtree.
bool inSubtree(const mjModel_* m, int b, int ancestor);

/// The derived facts of a checked description (every id of `v` valid). What only the derivation can see (arms
/// that do not mirror, feet off the ground at home) is appended to `problems`, the rest to `warnings`.
RobotFacts deriveFacts(const RobotDescription& d, const MjcfView& v, std::vector<Finding>& problems,
                       std::vector<Finding>& warnings);

}  // namespace centaur::robot::detail
