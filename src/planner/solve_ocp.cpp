#include "planner/solve_ocp.hpp"

#include <algorithm>

#include "planner/ipopt_solver.hpp"
#include "planner/riccati_backend.hpp"

namespace centaur::planner {

namespace {

// The iteration limit of riccati's attempt under `auto`: riccati needs at most ~170 iterations where it converges
// (docs/planner.md), and where it stalls it would otherwise spend solver.max_iter before Ipopt starts.
constexpr int kAutoRiccatiMaxIter = 300;

// riccati, and where it does not converge, Ipopt from the same start; the time of both counts, against
// solver.max_cpu_time too (Ipopt gets what riccati left, at least Ipopt's smallest limit).
SolveResult solveAuto(const Ocp& ocp, const SolverSettings& settings, const WarmStartPoint* warm) {
  SolverSettings first = settings;
  first.max_iter = std::min(settings.max_iter, kAutoRiccatiMaxIter);
  SolveResult r = solveWithRiccati(ocp, first, warm);
  if (r.info.solved()) return r;
  SolverSettings second = settings;
  second.max_cpu_time = std::max(0.01, settings.max_cpu_time - r.info.solve_time_s);
  SolveResult ip = solveWithIpopt(ocp, second, warm);
  ip.stats.first_attempt = {r.info.status, r.info.iterations, r.info.solve_time_s};
  ip.info.solve_time_s += r.info.solve_time_s;
  return ip;
}

SolveResult solveFrom(const Ocp& ocp, const SolverSettings& settings, const WarmStartPoint* warm) {
  SolveResult r = settings.backend == "ipopt"  ? solveWithIpopt(ocp, settings, warm)
                   : settings.backend == "auto" ? solveAuto(ocp, settings, warm)
                                                : solveWithRiccati(ocp, settings, warm);
  r.info.backend = r.stats.backend;  // stored with the primitive (solve_backend)
  return r;
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
