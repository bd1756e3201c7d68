#pragma once
// The planner tests' solve: an OCP with a named backend (ipopt | riccati | auto), without progress output, from
// the OCP's guess or from a decision vector alone.
#include <string>

#include <Eigen/Core>

#include "planner/solve_ocp.hpp"

namespace centaur::test {

inline planner::SolveResult solveWith(const planner::Ocp& ocp, planner::SolverSettings s, const std::string& backend,
                                      const Eigen::VectorXd* x0 = nullptr) {
  s.backend = backend;
  s.progress = false;
  return planner::solveOcp(ocp, s, x0);
}

}  // namespace centaur::test
