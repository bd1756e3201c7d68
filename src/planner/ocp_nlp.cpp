#include "planner/ocp_nlp.hpp"

#include <algorithm>
#include <cmath>

namespace centaur::planner {

OcpNlp::OcpNlp(const Ocp& ocp, bool user_scaling, const Eigen::VectorXd* x0, int threads)
    : ocp_(ocp), user_scaling_(user_scaling), x0_(x0 ? *x0 : ocp.guess()) {
  pattern_.n = ocp.numVariables();
  pattern_.m = ocp.numConstraints();
  pattern_.jac_rows = ocp.jacobianRows();
  pattern_.jac_cols = ocp.jacobianCols();
  pattern_.hess_rows = ocp.hessianRows();
  pattern_.hess_cols = ocp.hessianCols();
  split_c_ = ocp.numConstraintTerms();
  split_k_ = ocp.numCostTerms();
  if (threads >= 2) {
    // The caller also takes every cost term: half of the constraint work goes to the worker.
    double total = 0.0, acc = 0.0;
    for (int i = 0; i < ocp.numConstraintTerms(); ++i) total += ocp.constraintTermWork(i);
    split_c_ = 0;
    while (split_c_ < ocp.numConstraintTerms() && acc < 0.5 * total) acc += ocp.constraintTermWork(split_c_++);
    worker_ = std::make_unique<common::WorkerThread>();
    jac1_.resize(ocp.jacobianNonzeros());
    hess1_.resize(ocp.hessianNonzeros());
  }
}

void OcpNlp::bounds(Eigen::VectorXd& x_l, Eigen::VectorXd& x_u, Eigen::VectorXd& g_l, Eigen::VectorXd& g_u) const {
  x_l = ocp_.lowerBounds();
  x_u = ocp_.upperBounds();
  g_l = ocp_.constraintLower();
  g_u = ocp_.constraintUpper();
}

Eigen::VectorXd OcpNlp::variableScale() const {
  return user_scaling_ ? ocp_.scale() : Eigen::VectorXd::Ones(pattern_.n);
}

bool OcpNlp::objective(const Eigen::VectorXd& x, double& f) {
  f = ocp_.objective(x.data());
  return std::isfinite(f);
}

bool OcpNlp::constraints(const Eigen::VectorXd& x, Eigen::VectorXd& g) {
  g.resize(pattern_.m);
  ocp_.constraints(x.data(), g.data());
  return true;
}

bool OcpNlp::derivatives(const Eigen::VectorXd& x, double obj_factor, const Eigen::VectorXd& y, Eigen::VectorXd& grad,
                         double* jac, double* hess) {
  const int nj = ocp_.jacobianNonzeros(), nh = ocp_.hessianNonzeros();
  grad.setZero(pattern_.n);
  std::fill(jac, jac + nj, 0.0);
  std::fill(hess, hess + nh, 0.0);
  if (worker_) {
    grad1_.setZero(pattern_.n);
    std::fill(jac1_.begin(), jac1_.end(), 0.0);
    std::fill(hess1_.begin(), hess1_.end(), 0.0);
    worker_->run([&] {
      ocp_.addDerivatives(x.data(), obj_factor, y.data(), split_c_, ocp_.numConstraintTerms(), split_k_,
                          ocp_.numCostTerms(), scratch_[1], grad1_.data(), jac1_.data(), hess1_.data());
    });
  }
  ocp_.addDerivatives(x.data(), obj_factor, y.data(), 0, split_c_, 0, split_k_, scratch_[0], grad.data(), jac, hess);
  if (worker_) {
    worker_->wait();
    grad += grad1_;
    for (int k = 0; k < nj; ++k) jac[k] += jac1_[k];
    for (int k = 0; k < nh; ++k) hess[k] += hess1_[k];
  }
  ocp_.addConstantDerivatives(obj_factor, jac, hess);
  return true;
}

ocp_solver::StageLayout OcpNlp::stageLayout() const {
  const int N = ocp_.numIntervals(), stride = ocp_.nx() + ocp_.nu();
  ocp_solver::StageLayout l;
  l.num_stages = N + 1;
  for (int i = 0; i < pattern_.n; ++i) {
    const int k = std::min(i / stride, N);
    l.stage.push_back(k);
    l.is_state.push_back(k == N || i % stride < ocp_.nx());
  }
  return l;
}

std::vector<char> OcpNlp::fixedVariables() const {
  std::vector<char> f(pattern_.n);
  for (int i = 0; i < pattern_.n; ++i) f[i] = ocp_.lowerBounds()[i] == ocp_.upperBounds()[i];
  return f;
}

std::vector<char> OcpNlp::equalityRows() const {
  std::vector<char> e(pattern_.m);
  for (int r = 0; r < pattern_.m; ++r) e[r] = ocp_.constraintLower()[r] == ocp_.constraintUpper()[r];
  return e;
}

}  // namespace centaur::planner
