#pragma once
// A primal-dual interior-point method with Ipopt's algorithm (Waechter & Biegler, Math. Prog. 106, 2006):
// slacks for the inequality rows, log-barrier on every finite bound, Newton steps on the primal-dual
// equations with the bound multipliers and slacks eliminated (the remaining symmetric system goes to a
// KktSolver, e.g. the stage-wise Riccati one), inertia correction by a primal regularization delta_w (and a
// dual one delta_c for dependent rows) until the step is a descent direction, fraction-to-the-boundary rule,
// filter line search with second-order corrections and Ipopt's watchdog, and a barrier parameter that is either
// decreased monotonically (Fiacco-McCormick) or chosen each iteration by Mehrotra's predictor-corrector rule with
// the monotone mode as fallback. Termination tests as Ipopt's (tol on the scaled optimality error; constraint
// violation, dual infeasibility and complementarity on the unscaled ones).
#include <Eigen/Core>

#include <string>
#include <vector>

#include "ocp_solver/filter.hpp"
#include "ocp_solver/kkt_system.hpp"
#include "ocp_solver/nlp.hpp"

namespace centaur::ocp_solver {

struct IpmOptions {
  double tol = 1e-8;               ///< scaled optimality error (Ipopt `tol`)
  double constr_viol_tol = 1e-4;   ///< unscaled constraint violation
  double dual_inf_tol = 1.0;
  double compl_inf_tol = 1e-4;
  double acceptable_tol = 1e-6;    ///< "solved to an acceptable level" after acceptable_iter such iterations
  int acceptable_iter = 15;
  double acceptable_constr_viol_tol = 1e-2;
  double acceptable_compl_inf_tol = 1e-2;
  int max_iter = 3000;
  double max_cpu_time = 600.0;     ///< [s] wall time of the solve
  std::string mu_strategy = "adaptive";  ///< adaptive (Mehrotra, monotone fallback) | monotone
  double mu_init = 0.1;
  double bound_push = 1e-2, bound_frac = 1e-2;  ///< initial distance of x and the slacks to their bounds
  double bound_mult_init = 1.0;    ///< initial bound multipliers
  double bound_relax_factor = 1e-8;  ///< inequality bounds relaxed by this * max(1, |bound|) (Ipopt's default)
  double constr_mult_init_max = 1e3;
  bool progress = false;           ///< one line per iteration on stderr
};

/// Start from a known point (a neighbouring solution). With `x` alone, the multipliers start as in a cold solve
/// (bound_mult_init, least-squares y) and the barrier parameter at `mu_init`. With the neighbour's multipliers
/// as well (`y`, `z_l`, `z_u` all sized), the bound multipliers start from them (at least `mult_bound_push`),
/// the slack multipliers from y, and the barrier parameter decreases monotonically from `mu_init_primal_dual`:
/// the start is then already near the end of the neighbour's central path, which the adaptive rule would first
/// re-centre (Ipopt's warm_start_init_point with mu_strategy monotone).
struct WarmStart {
  Eigen::VectorXd x, y, z_l, z_u;  ///< unscaled; y, z_l, z_u may be empty
  double mu_init = 1e-4;           ///< barrier parameter to start from (x alone)
  double mu_init_primal_dual = 1e-8;  ///< barrier parameter to start from (x and multipliers)
  double bound_push = 1e-6;        ///< how far x is pushed off its bounds (relative, as bound_push)
  double mult_bound_push = 1e-3;   ///< floor of the bound and slack multipliers taken from z_l, z_u, y
  bool complementary_multipliers = false;  ///< x alone: bound multipliers mu / slack (else bound_mult_init)
  bool hasMultipliers(int n, int m) const { return y.size() == m && z_l.size() == n && z_u.size() == n; }
};

enum class IpmStatus {
  kSolved, kAcceptable, kMaxIterations, kMaxTime, kRestorationFailed, kInfeasible, kNumericalTrouble,
  kEvaluationError
};
const char* toString(IpmStatus s);

struct IpmStats {
  int iterations = 0;
  int factorizations = 0;       ///< including the retries of the inertia correction
  int solves = 0;               ///< KKT solves (steps, corrector, second-order corrections, refinement excluded)
  int restoration_iterations = 0;
  int mode_switches = 0;        ///< adaptive -> monotone
  int watchdog_starts = 0;      ///< after 10 shortened steps in a row: full steps measured from a stored point
  int watchdog_returns = 0;     ///< ... that did not pay off: back to the stored point
  int filter_resets = 0;        ///< Ipopt's filter reset heuristic emptied the line search's filter
  double time_total = 0.0;      ///< [s] wall
  double time_derivatives = 0.0;
  double time_functions = 0.0;  ///< objective and constraints (line search)
  double time_factor = 0.0;
  double time_solve = 0.0;
};

struct IpmResult {
  IpmStatus status = IpmStatus::kNumericalTrouble;
  Eigen::VectorXd x, y, z_l, z_u;  ///< unscaled
  double objective = 0.0;
  double constraint_violation = 0.0;  ///< max over rows and bounds, unscaled
  IpmStats stats;
};

IpmResult solveInteriorPoint(Nlp& nlp, KktSolver& kkt, const IpmOptions& options, const WarmStart* warm = nullptr);

}  // namespace centaur::ocp_solver
