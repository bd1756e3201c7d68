#pragma once
// Settings and result of an OCP solve, common to both backends: our interior-point method with the stage-wise
// (Riccati) KKT solver ("riccati", experimental) and Ipopt with MUMPS ("ipopt", the default and reference); "auto"
// runs riccati and, where it does not converge, Ipopt from the same start (docs/planner.md).
#include <string>

#include <Eigen/Core>

#include "common/yaml_reader.hpp"
#include "data/primitive.hpp"

namespace centaur::planner {

struct SolverSettings {
  std::string backend = "ipopt";  ///< ipopt | riccati | auto (riccati, then Ipopt unless it converged)
  double tol = 1e-8;              ///< scaled optimality error (Ipopt's `tol`)
  double constr_viol_tol = 1e-4;  ///< constraint violation (Ipopt's `constr_viol_tol`)
  int max_iter = 3000;
  double max_cpu_time = 600.0;    ///< [s]
  std::string hessian = "exact";  ///< exact | limited-memory (ipopt only)
  std::string mu_strategy = "adaptive";  ///< monotone | adaptive
  bool user_scaling = true;       ///< scale variables by their typical magnitude (Ocp::setScale)
  int print_level = 0;            ///< Ipopt's own output (0 = silent; ipopt only)
  /// riccati: "2" derivatives and factorizations on two threads, "1" on the calling one, "auto" on two while that
  /// pays (common/parallel_chooser.hpp). The solve is the same bit for bit.
  std::string threads = "auto";
  bool progress = false;          ///< one line per iteration on stderr
};

/// Read a `solver:` section (strict: finishes it). Keys and ranges as documented in config/*.yaml.
void readSolverSettings(centaur::YamlReader& section, SolverSettings& s);

/// What a backend reports besides SolveInfo (for benchmarks; -1 / 0 when a backend cannot tell).
struct SolveStats {
  std::string backend;
  int factorizations = -1;         ///< KKT factorizations, inertia-correction retries included
  double derivative_time_s = 0.0;  ///< gradient, Jacobian and Hessian evaluations [s wall]
  double function_time_s = 0.0;    ///< objective and constraint evaluations [s wall]
  double factor_time_s = -1.0;     ///< KKT factorizations [s wall]
  double linear_solve_time_s = -1.0;
  /// solver.backend auto, when Ipopt took over: how riccati's attempt ended (its status is empty otherwise).
  struct FirstAttempt {
    std::string status;
    int iterations = 0;
    double solve_time_s = 0.0;
  } first_attempt;
};

struct SolveResult {
  data::SolveInfo info;
  Eigen::VectorXd z;  ///< the final iterate (also when not converged)
  Eigen::VectorXd y;  ///< constraint multipliers (empty if the backend does not return them)
  Eigen::VectorXd z_l, z_u;  ///< lower / upper bound multipliers of the decision variables (>= 0; or empty)
  std::string ipopt_status;
  SolveStats stats;
};

/// A start from a neighbouring solution (unscaled, in the OCP's order): its decision vector and, when known,
/// its multipliers. With multipliers both backends start primal-dual (docs/planner.md, "Warm start").
struct WarmStartPoint {
  Eigen::VectorXd z;
  Eigen::VectorXd y, z_l, z_u;  ///< all sized to the OCP, or all empty (unknown)
  bool hasMultipliers() const { return y.size() > 0 && z_l.size() > 0 && z_u.size() > 0; }
  /// Multipliers for an OCP of n variables and m constraint rows (the backends use them only then).
  bool hasMultipliers(Eigen::Index n, Eigen::Index m) const {
    return y.size() == m && z_l.size() == n && z_u.size() == n;
  }
};

}  // namespace centaur::planner
