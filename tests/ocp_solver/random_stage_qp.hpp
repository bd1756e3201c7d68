#pragma once
// Random stage-structured KKT systems and their dense reference (tests of the Riccati recursion only): the dense
// matrix [H J'; J 0] in the recursion's variable and row order, the solution flattened into that order, the
// relative residual, the inertia from an eigen-decomposition, and random stage QPs with mixed, pure-state and
// pure-control rows.
#include <Eigen/Dense>

#include <random>
#include <vector>

#include "ocp_solver/riccati.hpp"

namespace centaur_test {

using centaur::ocp_solver::Inertia;
using centaur::ocp_solver::StageQp;
using centaur::ocp_solver::StageSolution;

struct Dense {
  Eigen::MatrixXd K;
  Eigen::VectorXd rhs;
  int n = 0, m = 0;
};

// [H J'; J 0] [z; y] = -[h; c] with z = [x_0, u_0, ..., x_N] and y = [eta_0, lambda_0, eta_1, lambda_1, ...].
inline Dense assemble(const std::vector<StageQp>& qp) {
  const int N = static_cast<int>(qp.size()) - 1;
  std::vector<int> off(N + 2, 0);
  int m = 0;
  for (int k = 0; k <= N; ++k) {
    off[k + 1] = off[k] + qp[k].nx + qp[k].nu;
    m += static_cast<int>(qp[k].C.rows()) + (k < N ? qp[k + 1].nx : 0);
  }
  Dense d;
  d.n = off[N + 1];
  d.m = m;
  d.K.setZero(d.n + m, d.n + m);
  d.rhs.setZero(d.n + m);
  int row = d.n;
  for (int k = 0; k <= N; ++k) {
    const StageQp& s = qp[k];
    const int n = s.nx + s.nu;
    d.K.block(off[k], off[k], n, n) = s.H;
    d.rhs.segment(off[k], n) = -s.h;
    const int mk = static_cast<int>(s.C.rows());
    d.K.block(row, off[k], mk, n) = s.C;
    d.rhs.segment(row, mk) = -s.c;
    row += mk;
    if (k < N) {
      const int nx1 = qp[k + 1].nx;
      d.K.block(row, off[k], nx1, s.nx) = s.A;
      d.K.block(row, off[k] + s.nx, nx1, s.nu) = s.B;
      d.K.block(row, off[k + 1], nx1, nx1) = -Eigen::MatrixXd::Identity(nx1, nx1);
      d.rhs.segment(row, nx1) = -s.b;
      row += nx1;
    }
  }
  d.K.bottomLeftCorner(m, d.n) = d.K.bottomLeftCorner(m, d.n);
  d.K.topRightCorner(d.n, m) = d.K.bottomLeftCorner(m, d.n).transpose();
  return d;
}

inline Eigen::VectorXd flatten(const std::vector<StageQp>& qp, const std::vector<StageSolution>& sol) {
  const int N = static_cast<int>(qp.size()) - 1;
  std::vector<double> z, y;
  for (int k = 0; k <= N; ++k) {
    for (int i = 0; i < sol[k].x.size(); ++i) z.push_back(sol[k].x[i]);
    for (int i = 0; i < sol[k].u.size(); ++i) z.push_back(sol[k].u[i]);
    for (int i = 0; i < sol[k].eta.size(); ++i) y.push_back(sol[k].eta[i]);
    for (int i = 0; i < sol[k].lambda.size(); ++i) y.push_back(sol[k].lambda[i]);
  }
  z.insert(z.end(), y.begin(), y.end());
  return Eigen::Map<Eigen::VectorXd>(z.data(), static_cast<Eigen::Index>(z.size()));
}

inline double relativeResidual(const Dense& d, const Eigen::VectorXd& v) {
  const double r = (d.K * v - d.rhs).cwiseAbs().maxCoeff();
  const double scale = d.K.cwiseAbs().maxCoeff() * v.cwiseAbs().maxCoeff() + d.rhs.cwiseAbs().maxCoeff();
  return r / scale;
}

inline Inertia denseInertia(const Eigen::MatrixXd& K) {
  const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(K).eigenvalues();
  const double tol = 1e-9 * std::max(1.0, ev.cwiseAbs().maxCoeff());
  Inertia in;
  for (int i = 0; i < ev.size(); ++i) (std::abs(ev[i]) <= tol ? in.zero : ev[i] > 0 ? in.positive : in.negative)++;
  return in;
}

enum class Curvature { kConvex, kIndefinite };

struct Gen {
  std::mt19937 rng;
  explicit Gen(unsigned seed) : rng(seed) {}
  double u() { return std::uniform_real_distribution<double>(-1.0, 1.0)(rng); }
  int i(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); }
  Eigen::MatrixXd mat(int r, int c) {
    Eigen::MatrixXd a(r, c);
    for (int j = 0; j < c; ++j)
      for (int k = 0; k < r; ++k) a(k, j) = u();
    return a;
  }
  Eigen::VectorXd vec(int n) { return mat(n, 1); }
};

// Random stage QP: each stage has mixed rows, pure-state rows (not at stage 0 unless x_0 is fixed) and
// pure-control rows; the row count stays below what the controls of the stage can absorb.
inline std::vector<StageQp> randomQp(Gen& g, int N, Curvature curv, bool fix_x0, int nx_max = 5, int nu_max = 4) {
  std::vector<int> nx(N + 1), nu(N + 1);
  for (int k = 0; k <= N; ++k) {
    nx[k] = g.i(1, nx_max);
    nu[k] = k < N ? g.i(1, nu_max) : 0;
  }
  std::vector<StageQp> qp(N + 1);
  for (int k = 0; k <= N; ++k) {
    const int n = nx[k] + nu[k];
    const int mixed = k < N ? g.i(0, std::max(0, nu[k] - 2)) : 0;
    const int state = (k > 0) ? g.i(0, std::min(1, nx[k])) : 0;
    const int control = k < N ? g.i(0, 1) : 0;
    const int fixed = (k == 0 && fix_x0) ? nx[0] : 0;
    const int m = mixed + state + control + fixed;
    StageQp& s = qp[k];
    s.resize(nx[k], nu[k], m, k < N ? nx[k + 1] : 0);
    Eigen::MatrixXd R = g.mat(n, n);
    s.H = curv == Curvature::kConvex ? Eigen::MatrixXd(R * R.transpose() + 0.1 * Eigen::MatrixXd::Identity(n, n))
                                     : Eigen::MatrixXd(R + R.transpose());
    s.h = g.vec(n);
    int row = 0;
    for (int j = 0; j < mixed; ++j) s.C.row(row++) = g.mat(1, n);
    for (int j = 0; j < state; ++j) s.C.row(row++).head(nx[k]) = g.mat(1, nx[k]);
    for (int j = 0; j < control; ++j) s.C.row(row++).tail(nu[k]) = g.mat(1, nu[k]);
    for (int j = 0; j < fixed; ++j) s.C(row++, j) = 1.0;
    s.c = g.vec(m);
    if (k < N) {
      s.A = g.mat(nx[k + 1], nx[k]);
      s.B = g.mat(nx[k + 1], nu[k]);
      s.b = g.vec(nx[k + 1]);
    }
  }
  return qp;
}

// A random instance whose KKT matrix is nonsingular (too many pure-state rows can over-determine x_0).
inline std::vector<StageQp> nonsingularQp(Gen& g, int N, Curvature curv, bool fix_x0, int nx_max = 5, int nu_max = 4) {
  for (;;) {
    auto qp = randomQp(g, N, curv, fix_x0, nx_max, nu_max);
    if (denseInertia(assemble(qp).K).zero == 0) return qp;
  }
}

}  // namespace centaur_test
