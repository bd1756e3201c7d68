#pragma once
// A dense reference for the KKT system of kkt_system.hpp (tests only): the matrix over the free variables and
// all rows, solved by LU; the inertia from an eigen-decomposition.
#include <Eigen/Dense>

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
    const Eigen::VectorXd s = K.fullPivLu().solve(rhs);
    dx.setZero(rx.size());
    for (int i = 0; i < nf; ++i) dx[free_vars[i]] = s[i];
    dy = s.tail(m);
  }

  Inertia inertia() const {
    const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(K).eigenvalues();
    const double tol = 1e-9 * std::max(1.0, ev.cwiseAbs().maxCoeff());
    Inertia in;
    for (int i = 0; i < ev.size(); ++i) (std::abs(ev[i]) <= tol ? in.zero : ev[i] > 0 ? in.positive : in.negative)++;
    return in;
  }
};

}  // namespace centaur_test
