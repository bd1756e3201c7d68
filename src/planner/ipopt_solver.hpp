#pragma once
// Ipopt adapter for an Ocp (TNLP interface). Exact sparse Jacobian and Lagrangian Hessian by default;
// "limited-memory" (L-BFGS) as an option.
#include <functional>
#include <string>

#include <Eigen/Core>

#include "planner/ocp.hpp"
#include "planner/solver_settings.hpp"

namespace centaur::planner {

/// Solve from the OCP's guess or from `x0` (a warm start: Ipopt starts closer to its bounds and with a small
/// barrier parameter); never throws for solver failures (they are reported in info.status).
SolveResult solveWithIpopt(const Ocp& ocp, const SolverSettings& settings, const Eigen::VectorXd* x0 = nullptr);

}  // namespace centaur::planner
