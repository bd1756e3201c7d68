#pragma once
// Ipopt adapter for an Ocp (TNLP interface). Exact sparse Jacobian and Lagrangian Hessian by default;
// "limited-memory" (L-BFGS) as an option.
#include <functional>
#include <string>

#include <Eigen/Core>

#include "common/yaml_reader.hpp"
#include "planner/ocp.hpp"
#include "data/primitive.hpp"

namespace centaur::planner {

struct SolverSettings {
  double tol = 1e-8;              ///< Ipopt `tol` (its default)
  double constr_viol_tol = 1e-4;  ///< Ipopt `constr_viol_tol` (its default)
  int max_iter = 3000;            ///< Ipopt `max_iter`
  double max_cpu_time = 600.0;    ///< [s]
  std::string hessian = "exact";  ///< exact | limited-memory
  std::string mu_strategy = "adaptive";  ///< monotone | adaptive
  bool user_scaling = true;       ///< scale variables by their typical magnitude (Ocp::setScale)
  int print_level = 0;            ///< Ipopt's own output (0 = silent)
  bool progress = false;          ///< one line per iteration on stderr
};

/// Read a `solver:` section (strict: finishes it). Keys and ranges as documented in config/*.yaml.
void readSolverSettings(centaur::YamlReader& section, SolverSettings& s);

struct SolveResult {
  data::SolveInfo info;
  Eigen::VectorXd z;  ///< the final iterate (also when not converged)
  std::string ipopt_status;
};

/// Solve; never throws for solver failures (they are reported in info.status).
SolveResult solveWithIpopt(const Ocp& ocp, const SolverSettings& settings);

}  // namespace centaur::planner
