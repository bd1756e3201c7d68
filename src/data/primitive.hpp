#pragma once
// A lower-body primitive: the planner's output and the online stage's input.
// Conventions (also stored as HDF5 attributes, see docs/primitive-format.md):
//   - SI units; world frame W: z up, ground plane z = 0 unless the primitive says otherwise.
//   - Foot order is the robot's wheel order: 0 = FL (wheel_1), 1 = FR (wheel_2), 2 = RL (wheel_3), 3 = RR (wheel_4).
//     (The authors' template used FL, FR, RR, RL; we do not.)
//   - "foot" is the template's point foot = the robot's wheel centre.
//   - Quaternions are stored w, x, y, z (MuJoCo's order; Eigen's coeffs() are x, y, z, w).
//   - Forces are those the environment exerts ON the robot at the foot, in W.
#include <Eigen/Core>

#include <map>
#include <string>
#include <vector>

#include "data/row_matrix.hpp"

namespace centaur::data {

/// How the solver ended; `status` is "solved" or the failure ("not_converged", "infeasible", ...).
struct SolveInfo {
  std::string status = "not_run";
  int iterations = 0;
  double solve_time_s = 0.0;
  double cost = 0.0;
  double max_constraint_violation = 0.0;
  std::string backend;  ///< the solver that produced it: "ipopt" or "riccati" (empty: not recorded, older files)
  bool solved() const { return status == "solved"; }
};

struct Primitive {
  std::string name;  ///< HDF5 group name, e.g. "squat-jump"

  // ---- 1 kHz samples (N rows), integrated from the knots with the same dynamics -----------------
  Eigen::VectorXd t;       ///< N        [s], starts at 0
  RowMatrix q;             ///< N x nq   template generalized coordinates [p(3), quat w,x,y,z (4), q_C (12)]
  RowMatrix nu;            ///< N x nv   template generalized velocities [v_W(3), omega_W(3), qdot_C(12)]
  RowMatrix base_pos;      ///< N x 3    [m] waist origin in W
  RowMatrix base_quat;     ///< N x 4    w, x, y, z, waist orientation W_R_B
  RowMatrix base_vel;      ///< N x 3    [m/s] in W
  RowMatrix base_omega;    ///< N x 3    [rad/s] in W
  RowMatrix foot_pos;      ///< N x 12   (4 x 3) [m] foot points in W
  RowMatrix foot_pos_rel;  ///< N x 12   (4 x 3) [m] foot points in the waist frame B (r_C)
  RowMatrix foot_vel_rel;  ///< N x 12   (4 x 3) [m/s] time derivative of foot_pos_rel, in B
  RowMatrix force;         ///< N x 12   (4 x 3) [N] contact forces on the robot, in W
  RowMatrix contact;       ///< N x 4    1 in contact (planned), 0 otherwise
  RowMatrix tau;           ///< N x 12   [N] prismatic leg joint forces (template actuation)

  // ---- raw OCP solution ("knots") ----------------------------------------------------------------
  Eigen::VectorXd knot_t;   ///< N_s+1  node times [s]
  RowMatrix knot_x;         ///< (N_s+1) x nx   states [q, nu]
  RowMatrix knot_u;         ///< N_s x nu_ctrl  controls [nu_dot(18), F(12), dt(1)]
  Eigen::VectorXd knot_dt;  ///< N_s    step sizes [s]

  // ---- the solver's multipliers at the knots (optional: all empty when not known) ---------------
  // In the order of the OCP that was solved (its constraint rows, its decision variables); a warm start of a
  // neighbour with the same OCP structure starts from them (docs/planner.md, "Warm start").
  Eigen::VectorXd mult_constraints;  ///< m  constraint multipliers y (Lagrangian f + y^T g)
  Eigen::VectorXd mult_lower;        ///< n  lower-bound multipliers of the decision variables (>= 0)
  Eigen::VectorXd mult_upper;        ///< n  upper-bound multipliers of the decision variables (>= 0)

  // ---- metadata (written as HDF5 attributes of the group) ---------------------------------------
  SolveInfo solve;
  std::string config_yaml;                               ///< the effective configuration
  std::map<std::string, double> scalars;                 ///< e.g. "total_mass", "waist_mass"
  std::map<std::string, std::vector<double>> vectors;    ///< e.g. "waist_com", "waist_inertia" (row-major 3x3)
  std::map<std::string, std::string> strings;            ///< e.g. "model_preset", "foot_names"

  Eigen::Index samples() const { return t.size(); }
};

}  // namespace centaur::data
