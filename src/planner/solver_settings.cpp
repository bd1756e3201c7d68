#include "planner/solver_settings.hpp"

namespace centaur::planner {

void readSolverSettings(YamlReader& s, SolverSettings& c) {
  s.get("backend", c.backend, {"riccati", "ipopt", "auto"});
  s.get("tol", c.tol, 1e-12, 1.0);
  s.get("constr_viol_tol", c.constr_viol_tol, 1e-12, 1.0);
  s.get("max_iter", c.max_iter, 0, 100000);
  s.get("max_cpu_time", c.max_cpu_time, 0.01, 1e6);
  s.get("hessian", c.hessian, {"exact", "limited-memory"});
  s.get("mu_strategy", c.mu_strategy, {"adaptive", "monotone"});
  s.get("user_scaling", c.user_scaling);
  s.get("print_level", c.print_level, 0, 12);
  s.get("threads", c.threads, {"auto", "1", "2"});
  if (c.hessian == "limited-memory" && c.backend != "ipopt") {
    s.fail("hessian", "limited-memory needs solver.backend: ipopt (the riccati backend, also tried first by auto, "
                      "uses the exact Hessian)");
  }
  s.finish();
}

}  // namespace centaur::planner
