#pragma once
// The "riccati" backend: our interior-point method (ocp_solver/interior_point.hpp, Ipopt's algorithm) with the
// stage-wise KKT solver (ocp_solver/stage_kkt.hpp) on an Ocp.
#include "planner/ocp.hpp"
#include "planner/solver_settings.hpp"

namespace centaur::planner {

/// Solve from the OCP's guess or from `warm` (ocp_solver::WarmStart: with the neighbour's multipliers a
/// primal-dual start on the monotone barrier from 1e-8; without, a small initial barrier parameter and
/// multipliers estimated by least squares). Never throws for solver failures (info.status); throws
/// RuntimeError if the OCP's structure does not fit the stage-wise solver.
SolveResult solveWithRiccati(const Ocp& ocp, const SolverSettings& settings, const WarmStartPoint* warm = nullptr);

}  // namespace centaur::planner
