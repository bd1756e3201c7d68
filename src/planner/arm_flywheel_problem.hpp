#pragma once
// The arm-flywheel OCP (paper Sec. "OCP Postural Task", eq. cost_function_posture_oc), on the planner's OCP
// layer and Ipopt:
//   state x = [q (7), qd (7)] of the fixed-base LEFT arm, control u = qdd (7), N_s intervals of the fixed period
//   T (normalised horizon: node k at t = k T / N_s), Direct Multiple Shooting with one RK4 step per interval
//   (exact for the double integrator, see arm_elements.hpp);
//   periodicity x_N = x_0 with the initial state free; optional phase anchor qd_0[shoulder pitch] = 0;
//   bounds: joint positions (MJCF range minus a margin), velocities and torques (scaled MJCF limits), each the
//   intersection of the left arm's and the mirrored right arm's limits, so the mirror replay is feasible too;
//   end-effector (hand tip) box in the pelvis frame;
//   cost sum_{k=0}^{N_s-1} [ gamma_h c_h(h_y,k) + gamma_qd qd_k^T qd_k + gamma_qdd qdd_k^T qdd_k ],
//   c_h = (h_y - h_d)^2 (tracking, default) or -h_y (linear); h about the torso_2 origin, pelvis axes.
// Node N is not in the cost (it equals node 0): the cost is invariant under a cyclic shift of the nodes.
#include <memory>

#include "model/serial_chain.hpp"
#include "planner/arm_flywheel_config.hpp"
#include "data/arm_trajectory.hpp"
#include "planner/solver_settings.hpp"
#include "planner/ocp.hpp"

namespace centaur::planner {

class ArmFlywheelProblem {
 public:
  /// Loads the arm from the MJCF (InputError for a bad model) and builds the OCP.
  explicit ArmFlywheelProblem(const ArmFlywheelConfig& config);

  const Ocp& ocp() const { return ocp_; }
  const model::SerialChain& chain() const { return chain_; }
  const ArmFlywheelConfig& config() const { return cfg_; }

  SolveResult solve(bool progress = false) const;
  /// Knots, 1 kHz samples (exact integration of the piecewise-constant qdd) and derived quantities.
  data::ArmTrajectory toTrajectory(const SolveResult& result) const;

 private:
  void buildLimits(const model::SerialChain& rchain);
  void buildVariables();
  void buildGuess();
  void buildConstraints();
  void buildCosts();
  ArmFlywheelConfig cfg_;
  model::SerialChain chain_;
  Eigen::VectorXd q_lo_, q_hi_, qd_max_, tau_max_;
  Eigen::VectorXd q_lo_model_, q_hi_model_, qd_max_model_, tau_max_model_;
  Ocp ocp_;
};

/// Build, solve and sample with the given configuration.
data::ArmTrajectory planArmFlywheel(const ArmFlywheelConfig& config, bool progress = false);

}  // namespace centaur::planner
