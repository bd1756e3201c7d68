#pragma once
// The lower-body jump OCP of the paper (eq. nlp_Diehl) on the template model, transcribed with Direct
// Multiple Shooting: state x_k = [q_k (19), nu_k (18)] at nodes 0..N, control u_k = [nu_dot_k (18), F_k (12),
// dt_k (1)] on intervals 0..N-1, RK4 with one step per interval, variable step size dt_k in [dt_min, dt_max].
//
// Contact schedule (per foot, per interval): a contact interval k applies F_k,i and pins the foot on the
// surface at nodes k and k+1 (position at every node: no drift accumulates); a touch-down node also asks
// for zero foot velocity (eq. no_slip); swing intervals have F = 0 (bounds) and keep the foot on the free side
// of every surface. Under-actuation (tau_u = 0) and torque bounds come from the template inverse dynamics at
// (x_k, u_k); workspace bounds are bounds on q_C (the legs are prismatic along the waist axes).
#include <vector>

#include "planner/solver_settings.hpp"
#include "planner/jump_config.hpp"
#include "planner/ocp.hpp"
#include "data/primitive.hpp"

namespace centaur::planner {

struct Surface {
  std::string name;
  Eigen::Vector3d normal;  ///< unit, pointing towards the robot
  double offset = 0.0;     ///< d in n . p + d = 0 for the FOOT POINT (wheel centre): physical surface + radius
  double mu = 0.5;
};

class JumpProblem {
 public:
  explicit JumpProblem(const JumpConfig& config);

  const JumpConfig& config() const { return cfg_; }
  const Ocp& ocp() const { return ocp_; }
  const std::vector<Surface>& surfaces() const { return surfaces_; }
  /// Surface index of foot i on interval k, or -1 in swing/flight.
  int contactSurface(int foot, int interval) const { return schedule_[foot][interval]; }

  /// Solve from the default guess, or from `x0` (a warm start, e.g. decisionVector() of a neighbouring primitive).
  SolveResult solve(bool progress, const Eigen::VectorXd* x0 = nullptr) const;
  /// Solve from a neighbouring solution (warmStart()): primal-dual when it holds multipliers.
  SolveResult solve(bool progress, const WarmStartPoint& warm) const;
  /// The decision vector of a primitive planned on the same horizon (its knots), for a warm start; InputError
  /// naming `source` if the numbers of intervals, states or controls differ.
  Eigen::VectorXd decisionVector(const data::Primitive& p, const std::string& source) const;
  /// decisionVector() plus the primitive's solver multipliers when it holds them for an OCP of this one's
  /// sizes (the same constraint rows and variables; else the start is primal only: hasMultipliers() false).
  WarmStartPoint warmStart(const data::Primitive& p, const std::string& source) const;
  /// Knots + 1 kHz resampling (integration of the same dynamics with the piecewise-constant controls).
  data::Primitive toPrimitive(const SolveResult& result, double sample_dt = 1e-3) const;

  // Index helpers into the decision vector.
  std::vector<int> idx(const char* var, int k, int first, int count) const;

 private:
  struct ResampleErrors {
    double end_error = 0.0;     ///< max |resampled end state - last knot|
    double max_residual = 0.0;  ///< largest under-actuation residual of the inverse dynamics at the samples
  };
  void fillKnots(const Eigen::VectorXd& z, data::Primitive& out) const;
  ResampleErrors resample(double sample_dt, data::Primitive& out) const;
  void fillMetadata(const Eigen::VectorXd& z, double sample_dt, const ResampleErrors& errors,
                    data::Primitive& out) const;
  void buildVariables();
  void buildDynamics();
  void buildContacts();
  void buildCosts();
  void buildGuess();

  JumpConfig cfg_;
  Ocp ocp_;
  int N_;
  std::vector<Surface> surfaces_;
  std::vector<std::vector<int>> schedule_;  // [foot][interval]
  double force_scale_;                       // m g
};

}  // namespace centaur::planner
