#include "planner/solve_ocp.hpp"

#include "planner/ipopt_solver.hpp"
#include "planner/riccati_backend.hpp"

namespace centaur::planner {

namespace {

SolveResult solveFrom(const Ocp& ocp, const SolverSettings& settings, const WarmStartPoint* warm) {
  if (settings.backend == "ipopt") return solveWithIpopt(ocp, settings, warm);
  return solveWithRiccati(ocp, settings, warm);
}

}  // namespace

SolveResult solveOcp(const Ocp& ocp, const SolverSettings& settings, const Eigen::VectorXd* x0) {
  if (!x0) return solveFrom(ocp, settings, nullptr);
  WarmStartPoint warm;
  warm.z = *x0;
  return solveFrom(ocp, settings, &warm);
}

SolveResult solveOcp(const Ocp& ocp, const SolverSettings& settings, const WarmStartPoint& warm) {
  return solveFrom(ocp, settings, &warm);
}

}  // namespace centaur::planner
