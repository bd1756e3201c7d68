#pragma once
// The "riccati" backend: our interior-point method (ocp_solver/interior_point.hpp, Ipopt's algorithm) with the
// stage-wise KKT solver (ocp_solver/stage_kkt.hpp) on an Ocp.
#include "planner/ocp.hpp"
#include "planner/solver_settings.hpp"

namespace centaur::planner {

/// Solve from the OCP's guess or from `x0` (a warm start: small initial barrier parameter, multipliers
/// estimated by least squares). Never throws for solver failures (info.status); throws RuntimeError if the
/// OCP's structure does not fit the stage-wise solver.
SolveResult solveWithRiccati(const Ocp& ocp, const SolverSettings& settings, const Eigen::VectorXd* x0 = nullptr);

}  // namespace centaur::planner
