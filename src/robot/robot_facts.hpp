#pragma once
// What centaur derives from a robot description and its MJCF, once, so that no stage types it again: the
// 5-mass template's parameters (waist = every body but the legs, its mass, CoM and inertia about that CoM;
// foot masses = leg masses; hip offsets = leg roots), the initial feet and wheel radii, the home base height,
// each arm's mirror signs and each arm joint's pitch authority, the Raibert directions and the joint limits
// (the MJCF's, overridden by robot.yaml). Everything is measured at the home keyframe with the base moved to
// the origin, upright: positions and axes are in the base frame B.
//
// checkRobot() validates the pair (every problem listed, not only the first) and, when it is sound, returns
// the facts; robotFacts() is the same for callers that want an exception (InputError with every problem).
#include <Eigen/Core>

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "model/robot_model.hpp"
#include "model/template_model.hpp"
#include "robot/robot_description.hpp"

namespace centaur::robot {

/// A stabilizer whose strongest joint moves less than this fraction of the robot's pitch inertia per rad/s
/// (centroidal angular momentum about y per joint rate, over the robot's pitch inertia): check warns.
inline constexpr double kLowPitchAuthority = 0.01;

struct ArmFacts {
  std::vector<double> mirror_signs;      ///< q_this = sign .* q_mirrored (empty if the arm mirrors none)
  std::vector<double> pitch_authority;   ///< [kg m^2/s per rad/s] centroidal angular momentum about y per joint rate
  std::vector<double> pitch_ratio;       ///< pitch_authority / the robot's pitch inertia about its CoM [-]
};

struct RobotFacts {
  double total_mass = 0.0;                     ///< [kg]
  std::vector<std::string> joint_names;        ///< the MJCF's hinges, in qpos order
  JointLimits limits;                          ///< the MJCF's, overridden by robot.yaml
  Eigen::VectorXd home_joints;                 ///< [rad] the home keyframe's joint positions
  double home_base_height = 0.0;               ///< [m] the base's height at home (feet on the ground)
  model::TemplateParams template_params;       ///< preset "derived"; foot_inertia and gravity as the defaults
  std::array<double, 4> leg_mass{};            ///< [kg] each leg's subtree (the template uses their mean)
  std::array<Eigen::Vector3d, 4> b_p_foot{};   ///< [m] foot centres at home, B
  std::array<double, 4> foot_radius{};         ///< [m] contact point below the centre
  std::array<Eigen::Vector3d, 4> centre_in_contact{};  ///< [m] each foot centre in its contact body's frame (0 when
                                                       ///< within 1 nm of the body's origin)
  std::array<std::vector<std::string>, 4> leg_joints;  ///< each leg's hinges, root to foot (qpos order)
  double pitch_inertia = 0.0;                  ///< [kg m^2] the whole robot's, about its CoM at home (y axis)
  std::vector<ArmFacts> arms;                  ///< as RobotDescription::arms
  std::vector<double> raibert_directions;      ///< sign of each raibert joint's pitch authority
  std::vector<std::string> gain_group;         ///< per joint, its gain group
};

struct Finding {
  std::string file;     ///< robot.yaml or the MJCF
  std::string key;      ///< robot.yaml key, or "" for the MJCF as a whole
  std::string message;
  std::string text() const;  ///< "<file>: key '<key>': <message>" (or "<file>: <message>")
};

struct CheckResult {
  std::vector<Finding> problems;  ///< any problem makes the description unusable (exit 2)
  std::vector<Finding> warnings;  ///< usable, but worth the user's attention
  std::optional<RobotFacts> facts;  ///< set when there is no problem
};

/// Validates the description against its MJCF and derives the facts. Never throws for bad input: every
/// problem found is listed (a missing name, a joint without limits, a body without inertia, missing IMU
/// sensors, non-torque or missing actuators, an MJCF feature MuJoCo 2.2.2 does not load, ...).
CheckResult checkRobot(const RobotDescription& d);

/// checkRobot() for callers that need the facts: InputError listing every problem if there is one.
RobotFacts robotFacts(const RobotDescription& d);

}  // namespace centaur::robot
