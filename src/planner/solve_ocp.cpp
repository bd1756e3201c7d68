#include "planner/solve_ocp.hpp"

#include "planner/ipopt_solver.hpp"
#include "planner/riccati_backend.hpp"

namespace centaur::planner {

SolveResult solveOcp(const Ocp& ocp, const SolverSettings& settings, const Eigen::VectorXd* x0) {
  if (settings.backend == "ipopt") return solveWithIpopt(ocp, settings, x0);
  return solveWithRiccati(ocp, settings, x0);
}

}  // namespace centaur::planner
