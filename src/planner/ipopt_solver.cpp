#include "planner/ipopt_solver.hpp"

#include <IpIpoptApplication.hpp>
#include <IpIpoptData.hpp>
#include <IpTNLP.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>

namespace centaur::planner {

namespace {

using Ipopt::Index;
using Ipopt::Number;

class OcpTnlp : public Ipopt::TNLP {
 public:
  OcpTnlp(const Ocp& ocp, const SolverSettings& s, const WarmStartPoint* warm, SolveResult& result)
      : ocp_(ocp), s_(s), warm_(warm), result_(result) {}

  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac_g, Index& nnz_h_lag, IndexStyleEnum& style) override {
    n = ocp_.numVariables();
    m = ocp_.numConstraints();
    nnz_jac_g = ocp_.jacobianNonzeros();
    nnz_h_lag = ocp_.hessianNonzeros();
    style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Index n, Number* x_l, Number* x_u, Index m, Number* g_l, Number* g_u) override {
    for (Index i = 0; i < n; ++i) {
      x_l[i] = std::isfinite(ocp_.lowerBounds()[i]) ? ocp_.lowerBounds()[i] : -2e19;
      x_u[i] = std::isfinite(ocp_.upperBounds()[i]) ? ocp_.upperBounds()[i] : 2e19;
    }
    for (Index j = 0; j < m; ++j) {
      g_l[j] = std::isfinite(ocp_.constraintLower()[j]) ? ocp_.constraintLower()[j] : -2e19;
      g_u[j] = std::isfinite(ocp_.constraintUpper()[j]) ? ocp_.constraintUpper()[j] : 2e19;
    }
    return true;
  }

  // The multipliers are asked for (warm_start_init_point) only when the warm start holds them.
  bool get_starting_point(Index n, bool init_x, Number* x, bool init_z, Number* z_L, Number* z_U, Index m,
                          bool init_lambda, Number* lambda) override {
    const bool multipliers = warm_ && warm_->hasMultipliers(n, m);
    if (!init_x || ((init_z || init_lambda) && !multipliers)) return false;
    const Eigen::VectorXd& start = warm_ ? warm_->z : ocp_.guess();
    for (Index i = 0; i < n; ++i) x[i] = start[i];
    if (init_z) {
      for (Index i = 0; i < n; ++i) z_L[i] = warm_->z_l[i], z_U[i] = warm_->z_u[i];
    }
    if (init_lambda) {
      for (Index j = 0; j < m; ++j) lambda[j] = warm_->y[j];
    }
    return true;
  }

  bool get_scaling_parameters(Number& obj_scaling, bool& use_x_scaling, Index n, Number* x_scaling,
                              bool& use_g_scaling, Index, Number*) override {
    obj_scaling = 1.0;
    use_x_scaling = true;
    for (Index i = 0; i < n; ++i) x_scaling[i] = 1.0 / ocp_.scale()[i];
    use_g_scaling = false;
    return true;
  }

  bool eval_f(Index, const Number* x, bool, Number& obj) override {
    const Timer t(result_.stats.function_time_s);
    obj = ocp_.objective(x);
    return std::isfinite(obj);
  }
  bool eval_grad_f(Index, const Number* x, bool, Number* g) override {
    const Timer t(result_.stats.derivative_time_s);
    ocp_.gradient(x, g);
    return true;
  }
  bool eval_g(Index, const Number* x, bool, Index, Number* g) override {
    const Timer t(result_.stats.function_time_s);
    ocp_.constraints(x, g);
    return true;
  }
  bool eval_jac_g(Index, const Number* x, bool, Index, Index nele, Index* iRow, Index* jCol, Number* values) override {
    if (!values) {
      for (Index k = 0; k < nele; ++k) {
        iRow[k] = ocp_.jacobianRows()[k];
        jCol[k] = ocp_.jacobianCols()[k];
      }
    } else {
      const Timer t(result_.stats.derivative_time_s);
      ocp_.jacobian(x, values);
    }
    return true;
  }
  bool eval_h(Index, const Number* x, bool, Number obj_factor, Index, const Number* lambda, bool, Index nele,
              Index* iRow, Index* jCol, Number* values) override {
    if (!values) {
      for (Index k = 0; k < nele; ++k) {
        iRow[k] = ocp_.hessianRows()[k];
        jCol[k] = ocp_.hessianCols()[k];
      }
    } else {
      const Timer t(result_.stats.derivative_time_s);
      ocp_.hessian(x, obj_factor, lambda, values);
    }
    return true;
  }

  bool intermediate_callback(Ipopt::AlgorithmMode mode, Index iter, Number obj_value, Number inf_pr, Number inf_du,
                             Number mu, Number, Number, Number, Number, Index ls_trials, const Ipopt::IpoptData*,
                             Ipopt::IpoptCalculatedQuantities*) override {
    if (s_.progress) {
      std::fprintf(stderr, "  iter %4d%s  cost %12.6e  infeas %9.2e  dual %9.2e  mu %8.1e  ls %d\n", static_cast<int>(iter),
                   mode == Ipopt::RestorationPhaseMode ? "r" : " ", obj_value, inf_pr, inf_du, mu,
                   static_cast<int>(ls_trials));
    }
    return true;
  }

  void finalize_solution(Ipopt::SolverReturn status, Index n, const Number* x, const Number* z_L, const Number* z_U, Index m,
                         const Number* g, const Number* lambda, Number obj_value, const Ipopt::IpoptData* ip_data,
                         Ipopt::IpoptCalculatedQuantities*) override {
    result_.z = Eigen::Map<const Eigen::VectorXd>(x, n);
    result_.y = Eigen::Map<const Eigen::VectorXd>(lambda, m);
    result_.z_l = Eigen::Map<const Eigen::VectorXd>(z_L, n);
    result_.z_u = Eigen::Map<const Eigen::VectorXd>(z_U, n);
    result_.info.cost = obj_value;
    result_.info.iterations = ip_data ? static_cast<int>(ip_data->iter_count()) : 0;
    double viol = 0.0;
    for (Index j = 0; j < m; ++j) {
      viol = std::max(viol, ocp_.constraintLower()[j] - g[j]);
      viol = std::max(viol, g[j] - ocp_.constraintUpper()[j]);
    }
    for (Index i = 0; i < n; ++i) {
      viol = std::max(viol, ocp_.lowerBounds()[i] - x[i]);
      viol = std::max(viol, x[i] - ocp_.upperBounds()[i]);
    }
    result_.info.max_constraint_violation = viol;
    switch (status) {
      case Ipopt::SUCCESS: result_.info.status = "solved"; break;
      case Ipopt::STOP_AT_ACCEPTABLE_POINT: result_.info.status = "solved_acceptable"; break;
      case Ipopt::MAXITER_EXCEEDED: result_.info.status = "max_iterations"; break;
      case Ipopt::CPUTIME_EXCEEDED: result_.info.status = "max_cpu_time"; break;
      case Ipopt::LOCAL_INFEASIBILITY: result_.info.status = "infeasible"; break;
      case Ipopt::RESTORATION_FAILURE: result_.info.status = "restoration_failed"; break;
      case Ipopt::DIVERGING_ITERATES: result_.info.status = "diverging"; break;
      default: result_.info.status = "failed"; break;
    }
  }

 private:
  // Adds the wall time of its scope to a counter.
  struct Timer {
    explicit Timer(double& acc) : acc_(acc), t0_(std::chrono::steady_clock::now()) {}
    ~Timer() { acc_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count(); }
    double& acc_;
    std::chrono::steady_clock::time_point t0_;
  };
  const Ocp& ocp_;
  const SolverSettings& s_;
  const WarmStartPoint* warm_;
  SolveResult& result_;
};

}  // namespace

SolveResult solveWithIpopt(const Ocp& ocp, const SolverSettings& s, const WarmStartPoint* warm) {
  SolveResult result;
  result.z = warm ? warm->z : ocp.guess();
  result.stats.backend = "ipopt";
  Ipopt::SmartPtr<Ipopt::TNLP> nlp = new OcpTnlp(ocp, s, warm, result);
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
  app->Options()->SetIntegerValue("print_level", s.print_level);
  app->Options()->SetStringValue("sb", "yes");  // no banner
  app->Options()->SetNumericValue("tol", s.tol);
  app->Options()->SetNumericValue("constr_viol_tol", s.constr_viol_tol);
  app->Options()->SetIntegerValue("max_iter", s.max_iter);
  app->Options()->SetNumericValue("max_cpu_time", s.max_cpu_time);
  app->Options()->SetStringValue("mu_strategy", s.mu_strategy);
  app->Options()->SetStringValue("linear_solver", "mumps");
  // MUMPS workspace: Ipopt's default asks for 1000 % more than MUMPS's estimate, which is allocated and touched
  // at every factorization (~0.5 s of system time per squat-jump solve). Ipopt enlarges it itself if MUMPS
  // reports that the workspace is too small (INFO(1) = -9), so a small margin is safe.
  app->Options()->SetIntegerValue("mumps_mem_percent", 10);
  app->Options()->SetStringValue("hessian_approximation", s.hessian);
  if (s.user_scaling) app->Options()->SetStringValue("nlp_scaling_method", "user-scaling");
  if (s.print_level >= 5) app->Options()->SetStringValue("print_timing_statistics", "yes");
  // Primal-dual warm start (multipliers that fit this OCP): from the neighbour's end of the central path.
  if (warm && warm->hasMultipliers(ocp.numVariables(), ocp.numConstraints())) {
    app->Options()->SetStringValue("warm_start_init_point", "yes");
    app->Options()->SetStringValue("mu_strategy", "monotone");
    app->Options()->SetNumericValue("mu_init", 1e-8);
    app->Options()->SetNumericValue("warm_start_bound_push", 1e-6);
    app->Options()->SetNumericValue("warm_start_bound_frac", 1e-6);
    app->Options()->SetNumericValue("warm_start_slack_bound_push", 1e-6);
    app->Options()->SetNumericValue("warm_start_slack_bound_frac", 1e-6);
    app->Options()->SetNumericValue("warm_start_mult_bound_push", 1e-3);
  } else if (warm) {  // from the knots alone: stay near them (no multipliers are known)
    app->Options()->SetNumericValue("mu_init", 1e-4);
    app->Options()->SetNumericValue("bound_push", 1e-6);
    app->Options()->SetNumericValue("bound_frac", 1e-6);
  }
  const auto t0 = std::chrono::steady_clock::now();
  Ipopt::ApplicationReturnStatus st = app->Initialize();
  if (st != Ipopt::Solve_Succeeded) {
    result.info.status = "ipopt_init_failed";
    return result;
  }
  st = app->OptimizeTNLP(nlp);
  result.info.solve_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (result.info.status == "not_run") result.info.status = "failed";
  result.ipopt_status = std::to_string(static_cast<int>(st));
  return result;
}

}  // namespace centaur::planner
