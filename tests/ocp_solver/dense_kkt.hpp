#pragma once
// A dense reference for the KKT system of kkt_system.hpp (tests only): the matrix over the free variables and
// all rows, solved by LU; the inertia from an eigen-decomposition.
#include <Eigen/Dense>

#include <memory>

#include "ocp_solver/kkt_system.hpp"

namespace centaur_test {

using centaur::ocp_solver::Inertia;
using centaur::ocp_solver::SparsePattern;

struct DenseKkt {
  Eigen::MatrixXd K;
  std::vector<int> free_vars;

  /// exact: rows whose d_c is ignored (kept at 0).
  DenseKkt(const SparsePattern& p, const std::vector<char>& fixed, const std::vector<char>& exact, const double* hess,
           const double* jac, const Eigen::VectorXd& dx, const Eigen::VectorXd& dc) {
    std::vector<int> col(p.n, -1);
    for (int v = 0; v < p.n; ++v)
      if (!fixed[v]) {
        col[v] = static_cast<int>(free_vars.size());
        free_vars.push_back(v);
      }
    const int nf = static_cast<int>(free_vars.size());
    K.setZero(nf + p.m, nf + p.m);
    for (std::size_t t = 0; t < p.hess_rows.size(); ++t) {
      const int a = col[p.hess_rows[t]], b = col[p.hess_cols[t]];
      if (a < 0 || b < 0) continue;
      K(a, b) += hess[t];
      if (a != b) K(b, a) += hess[t];
    }
    for (int i = 0; i < nf; ++i) K(i, i) += dx[free_vars[i]];
    for (std::size_t t = 0; t < p.jac_rows.size(); ++t) {
      const int c = col[p.jac_cols[t]];
      if (c < 0) continue;
      K(nf + p.jac_rows[t], c) += jac[t];
      K(c, nf + p.jac_rows[t]) += jac[t];
    }
    for (int r = 0; r < p.m; ++r)
      if (!(r < static_cast<int>(exact.size()) && exact[r])) K(nf + r, nf + r) = -dc[r];
  }

  void solve(const Eigen::VectorXd& rx, const Eigen::VectorXd& rc, Eigen::VectorXd& dx, Eigen::VectorXd& dy) const {
    const int nf = static_cast<int>(free_vars.size()), m = static_cast<int>(rc.size());
    Eigen::VectorXd rhs(nf + m);
    for (int i = 0; i < nf; ++i) rhs[i] = rx[free_vars[i]];
    rhs.tail(m) = rc;
    const Eigen::VectorXd s = K.partialPivLu().solve(rhs);
    dx.setZero(rx.size());
    for (int i = 0; i < nf; ++i) dx[free_vars[i]] = s[i];
    dy = s.tail(m);
  }

  /// Counted on S K S with S = diag(1 / sqrt(max_j |K_ij|)) (the same inertia by Sylvester's law), so that a
  /// large barrier diagonal does not make the small eigenvalues of the other rows look like zeros.
  Inertia inertia() const {
    Eigen::VectorXd s = Eigen::VectorXd::Ones(K.rows());
    for (int i = 0; i < K.rows(); ++i) {
      const double a = K.row(i).cwiseAbs().maxCoeff();
      if (a > 0.0) s[i] = 1.0 / std::sqrt(a);
    }
    const Eigen::MatrixXd Ks = s.asDiagonal() * K * s.asDiagonal();
    const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Ks).eigenvalues();
    const double tol = 1e-9 * std::max(1.0, ev.cwiseAbs().maxCoeff());
    Inertia in;
    for (int i = 0; i < ev.size(); ++i) (std::abs(ev[i]) <= tol ? in.zero : ev[i] > 0 ? in.positive : in.negative)++;
    return in;
  }
};

}  // namespace centaur_test

namespace centaur_test {

/// KktSolver on the dense matrix (tests of the interior-point method on small NLPs).
class DenseKktSolver final : public centaur::ocp_solver::KktSolver {
 public:
  DenseKktSolver(const SparsePattern& p, std::vector<char> fixed) : p_(p), fixed_(std::move(fixed)) {}
  centaur::ocp_solver::KktStatus factor(const double* hess, const double* jac, const Eigen::VectorXd& dx,
                                        const Eigen::VectorXd& dc) override {
    kkt_ = std::make_unique<DenseKkt>(p_, fixed_, exact_, hess, jac, dx, dc);
    const Inertia in = kkt_->inertia();
    last_ = in;
    if (in.zero > 0) return centaur::ocp_solver::KktStatus::kSingular;
    const bool ok = in.positive == static_cast<int>(kkt_->free_vars.size()) && in.negative == p_.m;
    return ok ? centaur::ocp_solver::KktStatus::kOk : centaur::ocp_solver::KktStatus::kWrongInertia;
  }
  void solve(const Eigen::VectorXd& rx, const Eigen::VectorXd& rc, Eigen::VectorXd& dx, Eigen::VectorXd& dy) override {
    kkt_->solve(rx, rc, dx, dy);
  }
  const std::vector<char>& alwaysExactRows() const override { return exact_; }
  Inertia inertia() const override { return last_; }

 private:
  SparsePattern p_;
  std::vector<char> fixed_, exact_;
  std::unique_ptr<DenseKkt> kkt_;
  Inertia last_;
};

}  // namespace centaur_test
