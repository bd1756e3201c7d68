#include "planner/riccati_backend.hpp"

#include <algorithm>
#include <thread>

#include "common/error.hpp"
#include "ocp_solver/interior_point.hpp"
#include "planner/ocp_nlp.hpp"

namespace centaur::planner {

SolveResult solveWithRiccati(const Ocp& ocp, const SolverSettings& s, const WarmStartPoint* start) {
  // Derivatives and factorizations on both cores of the planning machine (when there are two and solver.threads
  // allows): always with "2", with "auto" while the calling thread hardly waits for the second one or it pays.
  const int threads = s.threads != "1" && std::thread::hardware_concurrency() >= 2 ? 2 : 1;
  OcpNlp nlp(ocp, s.user_scaling, start ? &start->z : nullptr, threads);
  if (nlp.worker() && s.threads == "2") nlp.worker()->chooser().setMode(common::ParallelChooser::Mode::kParallel);
  SolveResult result;
  result.z = nlp.initialPoint();
  result.stats.backend = "riccati";
  std::unique_ptr<ocp_solver::StageKktSolver> kkt;
  try {
    kkt = std::make_unique<ocp_solver::StageKktSolver>(nlp.pattern(), nlp.stageLayout(), nlp.fixedVariables(),
                                                       nlp.equalityRows());
  } catch (const ocp_solver::StructureError& e) {
    throw RuntimeError(std::string("solver.backend riccati: ") + e.what() + " (use solver.backend: ipopt)");
  }
  kkt->setPipelined(nlp.worker());  // one second thread for both (none with one); never two polling for one core
  ocp_solver::IpmOptions o;
  o.tol = s.tol;
  o.constr_viol_tol = s.constr_viol_tol;
  o.max_iter = s.max_iter;
  o.max_cpu_time = s.max_cpu_time;
  o.mu_strategy = s.mu_strategy;
  o.progress = s.progress;
  ocp_solver::WarmStart warm;
  if (start) {
    warm.x = start->z;
    if (start->hasMultipliers(ocp.numVariables(), ocp.numConstraints())) {
      warm.y = start->y;
      warm.z_l = start->z_l;
      warm.z_u = start->z_u;
    }
  }
  const ocp_solver::IpmResult r = ocp_solver::solveInteriorPoint(nlp, *kkt, o, start ? &warm : nullptr);

  if (r.x.size() == result.z.size()) result.z = r.x;
  result.y = r.y;
  result.z_l = r.z_l;
  result.z_u = r.z_u;
  result.info.status = ocp_solver::toString(r.status);
  result.info.iterations = r.stats.iterations;
  result.info.solve_time_s = r.stats.time_total;
  result.info.cost = ocp.objective(result.z.data());
  Eigen::VectorXd g(ocp.numConstraints());
  ocp.constraints(result.z.data(), g.data());
  double viol = 0.0;
  for (int j = 0; j < g.size(); ++j)
    viol = std::max({viol, ocp.constraintLower()[j] - g[j], g[j] - ocp.constraintUpper()[j]});
  for (int i = 0; i < result.z.size(); ++i)
    viol = std::max({viol, ocp.lowerBounds()[i] - result.z[i], result.z[i] - ocp.upperBounds()[i]});
  result.info.max_constraint_violation = viol;
  result.stats.factorizations = r.stats.factorizations;
  result.stats.derivative_time_s = r.stats.time_derivatives;
  result.stats.function_time_s = r.stats.time_functions;
  result.stats.factor_time_s = r.stats.time_factor;
  result.stats.linear_solve_time_s = r.stats.time_solve;
  return result;
}

}  // namespace centaur::planner
