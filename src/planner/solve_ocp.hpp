#pragma once
// Solve an Ocp with the backend the settings name (solver.backend: riccati | ipopt).
#include "planner/ocp.hpp"
#include "planner/solver_settings.hpp"

namespace centaur::planner {

SolveResult solveOcp(const Ocp& ocp, const SolverSettings& settings, const Eigen::VectorXd* x0 = nullptr);

}  // namespace centaur::planner
