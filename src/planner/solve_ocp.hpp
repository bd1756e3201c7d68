#pragma once
// Solve an Ocp with the backend the settings name (solver.backend: riccati | ipopt | auto).
#include "planner/ocp.hpp"
#include "planner/solver_settings.hpp"

namespace centaur::planner {

/// From the OCP's guess, or from the decision vector `x0` alone (primal warm start).
SolveResult solveOcp(const Ocp& ocp, const SolverSettings& settings, const Eigen::VectorXd* x0 = nullptr);
/// From a neighbouring solution, primal-dual when `warm` holds its multipliers.
SolveResult solveOcp(const Ocp& ocp, const SolverSettings& settings, const WarmStartPoint& warm);

}  // namespace centaur::planner
