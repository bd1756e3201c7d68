#pragma once
// A smooth NLP as the interior-point method sees it:
//   min f(x)  s.t.  g_l <= g(x) <= g_u,  x_l <= x <= x_u
// (g_l == g_u: an equality row; x_l == x_u: a fixed variable; infinite bounds are +-infinity). Derivatives in the
// sparse structure of pattern(): the Jacobian of g and the lower triangle of the Lagrangian Hessian
// obj_factor * Hess f + sum_i y_i Hess g_i.
#include <Eigen/Core>

#include "ocp_solver/kkt_system.hpp"

namespace centaur::ocp_solver {

class Nlp {
 public:
  virtual ~Nlp() = default;
  virtual const SparsePattern& pattern() const = 0;
  virtual void bounds(Eigen::VectorXd& x_l, Eigen::VectorXd& x_u, Eigen::VectorXd& g_l, Eigen::VectorXd& g_u) const = 0;
  virtual Eigen::VectorXd initialPoint() const = 0;
  /// Typical magnitude of each variable (the method works on x / scale); ones by default.
  virtual Eigen::VectorXd variableScale() const { return Eigen::VectorXd::Ones(pattern().n); }

  /// false if the point cannot be evaluated (the line search then backtracks).
  virtual bool objective(const Eigen::VectorXd& x, double& f) = 0;
  virtual bool constraints(const Eigen::VectorXd& x, Eigen::VectorXd& g) = 0;
  /// Gradient, Jacobian values and Hessian values at one point (an implementation may share work between them).
  virtual bool derivatives(const Eigen::VectorXd& x, double obj_factor, const Eigen::VectorXd& y,
                           Eigen::VectorXd& grad, double* jac, double* hess) = 0;
};

}  // namespace centaur::ocp_solver
