#pragma once
// Configuration of a lower-body jump primitive (squat-jump, half-squat-jump): every key, its unit, default
// and allowed range is documented in docs/planner.md and in the shipped config/*.yaml files.
#include <yaml-cpp/yaml.h>

#include <array>
#include <vector>
#include <string>

#include <Eigen/Core>

#include "model/template_model.hpp"
#include "robot/robot_facts.hpp"
#include "planner/solver_settings.hpp"

namespace centaur::planner {

struct HorizonConfig {
  int intervals = 30;    ///< N_s
  int takeoff = 10;      ///< N_T: last interval of the initial stance
  int landing = 20;      ///< N_L: first interval of the landing stance
  double dt_min = 0.03;  ///< [s]
  double dt_max = 0.25;  ///< [s]
  double dt_init = 0.08; ///< [s] initial guess
};

struct WorkspaceConfig {  ///< foot points in the waist frame [m]
  Eigen::Vector2d front_x{0.1, 0.6};
  Eigen::Vector2d rear_x{-0.6, -0.1};
  Eigen::Vector2d left_y{0.1, 0.5};
  Eigen::Vector2d right_y{-0.5, -0.1};
  Eigen::Vector2d z{-0.76, -0.46};
  double reach = 0.0;  ///< [m] max hip -> foot distance (a sphere around each hip point; 0 = off)
};

struct ContactConfig {
  std::string friction = "pyramid";  ///< pyramid (linearized, as the paper) | cone
  double mu = 0.5;                   ///< Coulomb friction coefficient (ground)
  double mu_wall = 1.0;              ///< Coulomb friction coefficient (wall)
  double force_threshold = 0.0;      ///< F_thr [N]: minimum normal force in contact
  double force_max = 1.0e4;          ///< [N] bound on every force component
  std::string touchdown = "same_position";  ///< squat-jump landing: same_position | free (anywhere on the ground)
};

struct LimitsConfig {
  double leg_force = 1500.0;   ///< [N] |tau| bound of each prismatic leg joint (torque bounds)
  double velocity = 100.0;     ///< bound on |nu| components
  double acceleration = 100.0; ///< bound on |nu_dot| components
};

struct CostConfig {
  double base_height = 50.0;         ///< gamma_p: (z - target)^2 on nodes N_T+1..N_L
  double base_velocity = 0.0;        ///< gamma_nu: nu^T nu on nodes N_T+1..N_L
  double joint_velocity = 1.0;       ///< gamma_qdot: qdot_C^T qdot_C on nodes N_T+1..N_s
  double force_rate = 1.0;           ///< gamma_Fdot: |F_k+1 - F_k|^2, intervals N_L+1..N_s-2
  double acceleration_rate = 1.0e-3; ///< gamma_nuddot: |nu_dot_k+1 - nu_dot_k|^2, intervals 0..N_s-2
  double base_orientation = 0.0;     ///< |rho - rho_0|^2 on every node (the authors' script: 100)
  double base_pose = 0.0;            ///< |p - p_0|^2 + |rho - rho_0|^2 on nodes N_T+1..N_s (half-squat-jump)
  // Not in the paper's cost (our additions, documented in docs/planner.md):
  double stance_foot_velocity = 100.0;  ///< |w_pdot_foot|^2 at every node where the foot is in contact: keeps
                                        ///< stance feet still BETWEEN shooting nodes (positions are pinned at nodes)
  double velocity_regularization = 0.0; ///< nu^T nu on every node
  double base_angular_velocity = 1000.0;///< |omega_u|^2 on every node: the template's legs accelerate in the waist
                                        ///< frame, so waist rotation makes the motion between knots deviate from
                                        ///< the dynamics enforced at the knots
  double last_interval = 1.0e-3;        ///< dt_{N_s-1}^2 [1/s^2]: the robot is at rest through the last interval,
                                        ///< so nothing else fixes its length (squat jump; 0 for the half-squat jump)
  double landing_steps = 0.0;           ///< [1/s] sum of (dt_max - dt_k), k = N_L..N_s-1: a reward for long steps
                                        ///< after the landing, where the robot comes to rest and little else fixes
                                        ///< their lengths (off by default: it moves the steps that are not free)
};

struct JumpConfig {
  std::string primitive = "squat-jump";  ///< squat-jump | half-squat-jump
  std::string robot = "centauro";        ///< key `robot`: a shipped robot's name or a robot.yaml (docs/robots.md);
                                         ///< after loadJumpConfig() the description's name
  std::string robot_hash;                ///< the description's hash (robot/robot_description.hpp), "" if not loaded
  model::TemplateParams model;
  HorizonConfig horizon;
  std::array<Eigen::Vector3d, 4> feet;  ///< initial foot points in the waist frame [m] (FL, FR, RL, RR)
  double wheel_radius = 0.078;          ///< [m] foot points are wheel centres, surfaces offset by this
  WorkspaceConfig workspace;
  ContactConfig contact;
  LimitsConfig limits;
  double target_height = 0.9;   ///< [m] squat-jump: waist height (world z) to reach in flight
  double wall_distance = 0.15;  ///< [m] half-squat-jump: wall (foot-point plane) behind the rear wheel centres
  double wall_height = 0.0;     ///< [m] half-squat-jump: height (world z) of the rear wheel centres on the wall from
                                ///< their touch-down on; 0 = free (the optimizer places them)
  CostConfig cost;
  SolverSettings solver;
  std::string source = "<defaults>";  ///< where the configuration came from (for messages)
  YAML::Node effective;               ///< the effective configuration (saved with the output)

  // Derived quantities (world frame, ground z = 0, waist starts above the origin).
  double initialWaistHeight() const;            ///< wheel_radius - mean foot z
  Eigen::Vector3d initialFootWorld(int i) const;
  double wallX() const;                          ///< physical wall surface x [m]
};

/// The embedded defaults of a primitive as YAML text (what `make demo` runs).
std::string defaultJumpYaml(const std::string& primitive);
/// The jump primitives the planner knows.
std::vector<std::string> jumpPrimitiveNames();
/// Defaults of `primitive`, then the robot's layer (robotPlannerLayer of the key `robot`), then the file (if any),
/// then each --set override; validated. Throws InputError naming the file, key and allowed range.
JumpConfig loadJumpConfig(const std::string& primitive, const std::string& file,
                          const std::vector<std::string>& overrides);
/// Parse an already merged YAML tree (validation only); `derived` is what model preset `derived` means.
JumpConfig parseJumpConfig(const YAML::Node& root, const std::string& label,
                           const model::TemplateParams* derived = nullptr);

/// What the robot brings to a planner configuration: model preset `derived`, its feet at home as the initial
/// stance, its foot radius, then the sections `all` and `<primitive>` of planner.yaml beside its robot.yaml.
YAML::Node robotPlannerLayer(const robot::RobotDescription& d, const robot::RobotFacts& f, const std::string& primitive);

}  // namespace centaur::planner
