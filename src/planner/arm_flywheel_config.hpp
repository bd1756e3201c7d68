#pragma once
// Configuration of the arm-flywheel OCP (paper Sec. "OCP Postural Task", stabilizer 3): every key, its unit,
// default and range is documented in config/arm-flywheel.yaml (the same text is embedded here as defaults).
#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include <Eigen/Core>

#include "planner/solver_settings.hpp"

namespace centaur::planner {

struct ArmFlywheelConfig {
  std::string primitive = "arm-flywheel";
  std::string mjcf;                 ///< "" = the shipped models/centauro/centauro.xml
  int intervals = 40;               ///< N_s shooting intervals over the normalised horizon [0, 1]
  double period = 1.0;              ///< [s] T: one period of the arm motion (fixed)
  double position_margin = 0.05;    ///< [rad] kept from each end of every joint range
  double velocity_scale = 0.9;      ///< fraction of the MJCF velocity limits
  double torque_scale = 0.8;        ///< fraction of the MJCF effort limits
  Eigen::Vector2d ws_x{0.40, 1.00};  ///< [m] end-effector (hand tip) box in the pelvis frame
  Eigen::Vector2d ws_y{0.10, 0.70};
  Eigen::Vector2d ws_z{0.15, 1.10};
  double com_x_offset = 2.0;        ///< [m] |arm CoM x - its home value| bound (pelvis frame); 2 = off
  std::string momentum_mode = "tracking";  ///< tracking: gamma_h (h_y - h_d)^2 | linear: -gamma_h h_y
  double gamma_h = 1.0;             ///< momentum weight
  double h_d = 5.0;                 ///< [N m s] tracking target (tracking mode only)
  double gamma_qd = 0.02;           ///< weight of qd^T qd
  double gamma_qdd = 1.0e-4;        ///< weight of qdd^T qdd (our addition: smooth torques)
  bool phase_anchor = false;        ///< qd_0 of the shoulder pitch = 0 (pins the free phase; slower to converge)
  double sample_dt = 0.001;         ///< [s] spacing of the stored samples
  SolverSettings solver;
  std::string source = "<defaults>";
  YAML::Node effective;
};

/// The embedded defaults (config/arm-flywheel.yaml without comments).
std::string defaultArmFlywheelYaml();
/// Defaults, then the file (if any), then each --set override; validated (InputError naming file/key/range).
ArmFlywheelConfig loadArmFlywheelConfig(const std::string& file, const std::vector<std::string>& overrides);
ArmFlywheelConfig parseArmFlywheelConfig(const YAML::Node& root, const std::string& label);

}  // namespace centaur::planner
