#pragma once
// Ipopt adapter for an Ocp (TNLP interface). Exact sparse Jacobian and Lagrangian Hessian by default;
// "limited-memory" (L-BFGS) as an option.
#include <functional>
#include <string>

#include <Eigen/Core>

#include "planner/ocp.hpp"
#include "planner/solver_settings.hpp"

namespace centaur::planner {

/// Solve from the OCP's guess or from `warm` (Ipopt starts closer to its bounds and with a small barrier
/// parameter; with the neighbour's multipliers also from those: warm_start_init_point, monotone barrier from
/// 1e-8); never throws for solver failures (they are reported in info.status).
SolveResult solveWithIpopt(const Ocp& ocp, const SolverSettings& settings, const WarmStartPoint* warm = nullptr);

}  // namespace centaur::planner
