#pragma once
// A periodic arm trajectory (the arm-flywheel plan of stabilizer 3) as stored in the primitive database
// (HDF5 group "arm-flywheel", schema in docs/primitive-format.md).
// Conventions: SI units; frame R = the pelvis frame (x forward, y left, z up); the arm is the LEFT arm
// (j_arm1_1..7) of a fixed-base model whose torso_2 is held at its home pose; the right arm replays the mirror
// image q_right = mirror .* q_left (see armMirrorSigns()). The last sample equals the first (periodic).
#include <Eigen/Core>

#include <string>
#include <vector>

#include "data/primitive.hpp"

namespace centaur::data {

struct ArmTrajectory {
  std::string name = "arm-flywheel";
  std::vector<std::string> joint_names;  ///< the planned arm's joints (7)
  double period = 1.0;                   ///< [s] T

  // ---- samples (N rows, uniform in time over one period, t[N-1] = T) ----
  Eigen::VectorXd t;  ///< N [s]
  RowMatrix q;        ///< N x 7 [rad]
  RowMatrix qd;       ///< N x 7 [rad/s]
  RowMatrix qdd;      ///< N x 7 [rad/s^2]
  RowMatrix tau;      ///< N x 7 [Nm] inverse dynamics of the fixed-base arm (gravity, armature)
  RowMatrix h_ang;    ///< N x 3 [N m s] angular momentum of the arm about momentum_point, R axes
  RowMatrix ee_pos;   ///< N x 3 [m] end-effector (hand tip) point in R

  // ---- the OCP's knots ----
  Eigen::VectorXd knot_t;  ///< N_s + 1 [s]
  RowMatrix knot_x;        ///< (N_s + 1) x 14 [q, qd]
  RowMatrix knot_u;        ///< N_s x 7 qdd

  // ---- bounds used by the OCP (7 each) and model facts ----
  Eigen::VectorXd q_min, q_max, qd_max, tau_max;           ///< effective (margins applied)
  Eigen::VectorXd q_min_model, q_max_model, qd_max_model, tau_max_model;  ///< MJCF limits of the planned arm
  Eigen::Vector3d ee_box_min = Eigen::Vector3d::Zero(), ee_box_max = Eigen::Vector3d::Zero();  ///< [m] in R
  Eigen::Vector3d momentum_point = Eigen::Vector3d::Zero();  ///< [m] in R
  std::string reference_frame = "pelvis";
  std::string ee_frame = "ball1_tip";

  SolveInfo solve;
  std::string config_yaml;

  Eigen::Index samples() const { return t.size(); }
};

/// Sign of each arm joint in the sagittal mirror left -> right: q_right = s .* q_left (joints 2, 3, 5, 7 flip).
inline Eigen::Matrix<double, 7, 1> armMirrorSigns() {
  Eigen::Matrix<double, 7, 1> s;
  s << 1, -1, -1, 1, -1, 1, -1;
  return s;
}

}  // namespace centaur::data
