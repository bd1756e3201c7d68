#pragma once
// Test-only generators of dense QPs: random feasible problems with degenerate rows (answer from the Ipopt oracle),
// rank-deficient problems whose unique answer is known by construction, unbounded problems with a known ray, and
// the relative KKT residual of an answer.
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <Eigen/QR>

#include "ipopt_oracle.hpp"
#include "qp/qp_solver.hpp"

namespace centaur::test {

using Eigen::MatrixXd;
using Eigen::VectorXd;
constexpr double kInf = std::numeric_limits<double>::infinity();

inline QpStatus solveQp(QpSolver& s, const DenseQp& qp) {
  return s.solve(qp.H, qp.g, qp.A_eq, qp.b_eq, qp.C, qp.c_lo, qp.c_up, qp.x_lo, qp.x_up);
}

/// Normwise relative KKT residual of (x, y), scaled like the rounding errors of each term (they grow with ||x||):
/// stationarity / max(1, ||H||_inf ||x||_inf, ||g||_inf, |y_i| ||row_i||_1), a violation / max(1, |bound|,
/// ||row||_1 ||x||_inf), complementarity as the product of the relative multiplier |y_i| ||row_i||_1 / (that
/// stationarity scale) and the relative distance to its bound; a multiplier on an infinite bound counts in full.
inline double kktResidualRelative(const DenseQp& qp, const QpSolver& s) {
  const VectorXd x = s.x();
  const VectorXd y_eq = s.yEq(), y_in = s.yIneq();
  const bool box = qp.x_lo.size() > 0;
  const double x_max = x.size() > 0 ? x.cwiseAbs().maxCoeff() : 0.0;
  VectorXd stat = qp.H * x + qp.g - qp.A_eq.transpose() * y_eq - qp.C.transpose() * y_in;
  if (box) stat -= s.yBox();
  double scale = std::max({1.0, qp.H.cwiseAbs().rowwise().sum().maxCoeff() * x_max, qp.g.cwiseAbs().maxCoeff()});
  for (int i = 0; i < qp.A_eq.rows(); ++i) scale = std::max(scale, std::abs(y_eq[i]) * qp.A_eq.row(i).cwiseAbs().sum());
  for (int i = 0; i < qp.C.rows(); ++i) scale = std::max(scale, std::abs(y_in[i]) * qp.C.row(i).cwiseAbs().sum());
  if (box) scale = std::max(scale, s.yBox().cwiseAbs().maxCoeff());
  double res = stat.cwiseAbs().maxCoeff() / scale;
  auto side = [&](double v, double lo, double up, double y, double row1) {
    double r = 0.0;
    const double lo_s = std::max({1.0, std::abs(lo), row1 * x_max}), up_s = std::max({1.0, std::abs(up), row1 * x_max});
    if (std::isfinite(lo)) r = std::max(r, (lo - v) / lo_s);
    if (std::isfinite(up)) r = std::max(r, (v - up) / up_s);
    const double weight = std::abs(y) * row1 / scale;  // complementarity: |y| |v - bound|, both relative
    if (y > 0.0) r = std::max(r, std::isfinite(lo) ? weight * std::abs(v - lo) / lo_s : weight);
    if (y < 0.0) r = std::max(r, std::isfinite(up) ? weight * std::abs(v - up) / up_s : weight);
    return r;
  };
  for (int i = 0; i < qp.A_eq.rows(); ++i) {
    const double b = qp.b_eq[i];
    res = std::max(res, side(qp.A_eq.row(i).dot(x), b, b, 0.0, qp.A_eq.row(i).cwiseAbs().sum()));
  }
  const VectorXd cx = qp.C * x;
  for (int i = 0; i < qp.C.rows(); ++i)
    res = std::max(res, side(cx[i], qp.c_lo[i], qp.c_up[i], y_in[i], qp.C.row(i).cwiseAbs().sum()));
  if (box)
    for (int j = 0; j < qp.n(); ++j) res = std::max(res, side(x[j], qp.x_lo[j], qp.x_up[j], s.yBox()[j], 1.0));
  return res;
}

/// Relative KKT residual of (x, y) for the convention H x + g = A_eq' y_eq + C' y_in + y_box:
// max of stationarity, primal violation, dual sign violation and complementarity, each scaled by the data.
inline double kktResidual(const DenseQp& qp, const QpSolver& s) {
  const VectorXd& x = s.x();
  const VectorXd y_eq = s.yEq(), y_in = s.yIneq();
  VectorXd stat = qp.H * x + qp.g - qp.A_eq.transpose() * y_eq - qp.C.transpose() * y_in;
  const bool box = qp.x_lo.size() > 0;
  if (box) stat -= s.yBox();
  const double scale = 1.0 + (qp.H * x).cwiseAbs().maxCoeff() + qp.g.cwiseAbs().maxCoeff();
  double res = stat.cwiseAbs().maxCoeff() / scale;
  if (qp.A_eq.rows() > 0) {
    res = std::max(res, ((qp.A_eq * x - qp.b_eq).array().abs() / (1.0 + qp.b_eq.array().abs())).maxCoeff());
  }
  auto side = [&](double v, double lo, double up, double y) {
    double r = 0.0;
    if (std::isfinite(lo)) r = std::max(r, (lo - v) / (1.0 + std::abs(lo)));
    if (std::isfinite(up)) r = std::max(r, (v - up) / (1.0 + std::abs(up)));
    if (y > 0.0) r = std::max(r, std::isfinite(lo) ? y * std::abs(v - lo) / (1.0 + std::abs(lo)) : y);
    if (y < 0.0) r = std::max(r, std::isfinite(up) ? -y * std::abs(v - up) / (1.0 + std::abs(up)) : -y);
    return r;
  };
  const VectorXd cx = qp.C * x;
  for (int i = 0; i < qp.C.rows(); ++i) res = std::max(res, side(cx[i], qp.c_lo[i], qp.c_up[i], y_in[i]));
  if (box)
    for (int j = 0; j < qp.n(); ++j) res = std::max(res, side(x[j], qp.x_lo[j], qp.x_up[j], s.yBox()[j]));
  return res;
}

/// A random feasible problem (rel_reg >= 0: H of rank n/2 plus rel_reg * max(H_ii) * I, and with least_squares g
/// in the range of that rank-n/2 part, as in a regularised least-squares cost): a point x0 satisfies every constraint; rows are made active at x0, redundant,
// duplicated (also with flipped sign), rank deficient, one-sided or free; H sometimes ill-conditioned.
inline DenseQp randomFeasible(std::mt19937& rng, int n_max = 25, double rel_reg = -1.0, bool least_squares = false) {
  std::uniform_int_distribution<int> dn(1, n_max);
  std::normal_distribution<double> N(0.0, 1.0);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  const int n = dn(rng);
  DenseQp qp;
  VectorXd x0(n);
  for (int j = 0; j < n; ++j) x0[j] = N(rng);
  // Hessian: full rank, or low rank plus a small diagonal (ill-conditioned).
  // rel_reg >= 0: rank n/2 plus rel_reg times the largest diagonal entry (relative regularisation).
  const int k = rel_reg >= 0.0 || U(rng) < 0.3 ? std::max(1, n / 2) : n;
  MatrixXd M(k, n);
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < n; ++j) M(i, j) = N(rng);
  if (rel_reg >= 0.0) {
    qp.H = M.transpose() * M / k;
    qp.H += rel_reg * qp.H.diagonal().maxCoeff() * MatrixXd::Identity(n, n);
  } else {
    const double delta = U(rng) < 0.3 ? 1e-4 : 0.1 + U(rng);
    qp.H = M.transpose() * M / k + delta * MatrixXd::Identity(n, n);
  }
  qp.g.resize(n);
  for (int j = 0; j < n; ++j) qp.g[j] = 3.0 * N(rng);
  if (rel_reg >= 0.0 && least_squares) {  // g = -M' b / k: the cost ||M x - b||^2 / (2k) + regularisation
    VectorXd b(k);
    for (int i = 0; i < k; ++i) b[i] = 3.0 * N(rng);
    qp.g = -M.transpose() * b / k;
  }
  // Equalities, possibly rank deficient (rows that combine earlier rows, more rows than variables).
  const int m_eq = std::uniform_int_distribution<int>(0, U(rng) < 0.2 ? n + 2 : std::max(0, n - 1))(rng);
  qp.A_eq.resize(m_eq, n);
  for (int i = 0; i < m_eq; ++i) {
    if (i >= 2 && (U(rng) < 0.25 || i >= n)) {
      qp.A_eq.row(i) = N(rng) * qp.A_eq.row(i - 1) + N(rng) * qp.A_eq.row(i - 2);
    } else {
      for (int j = 0; j < n; ++j) qp.A_eq(i, j) = N(rng);
    }
  }
  qp.b_eq = qp.A_eq * x0;
  // Two-sided inequality rows.
  const int m_in = std::uniform_int_distribution<int>(0, 2 * n)(rng);
  qp.C.resize(m_in, n);
  qp.c_lo.resize(m_in);
  qp.c_up.resize(m_in);
  for (int i = 0; i < m_in; ++i) {
    const double kind = U(rng);
    if (i >= 1 && kind < 0.08) {  // duplicate of the previous row
      qp.C.row(i) = qp.C.row(i - 1);
      qp.c_lo[i] = qp.c_lo[i - 1];
      qp.c_up[i] = qp.c_up[i - 1];
      continue;
    }
    if (i >= 1 && kind < 0.14) {  // the previous row negated (bounds swapped)
      qp.C.row(i) = -qp.C.row(i - 1);
      qp.c_lo[i] = -qp.c_up[i - 1];
      qp.c_up[i] = -qp.c_lo[i - 1];
      continue;
    }
    if (i >= 2 && kind < 0.2) {  // a combination of two earlier rows
      qp.C.row(i) = qp.C.row(i - 1) + 0.5 * qp.C.row(i - 2);
    } else {
      for (int j = 0; j < n; ++j) qp.C(i, j) = N(rng);
    }
    const double c = qp.C.row(i).dot(x0);
    const double t = U(rng);
    if (t < 0.2) {  // active lower at x0
      qp.c_lo[i] = c;
      qp.c_up[i] = U(rng) < 0.5 ? kInf : c + U(rng);
    } else if (t < 0.4) {  // active upper at x0
      qp.c_lo[i] = U(rng) < 0.5 ? -kInf : c - U(rng);
      qp.c_up[i] = c;
    } else if (t < 0.45) {  // equality written as an inequality row
      qp.c_lo[i] = qp.c_up[i] = c;
    } else if (t < 0.5) {  // free row
      qp.c_lo[i] = -kInf;
      qp.c_up[i] = kInf;
    } else {  // slack both sides, one side maybe infinite
      qp.c_lo[i] = U(rng) < 0.2 ? -kInf : c - 0.5 * U(rng);
      qp.c_up[i] = U(rng) < 0.2 ? kInf : c + 0.5 * U(rng);
    }
  }
  // Box bounds half of the time, some active at x0.
  if (U(rng) < 0.5) {
    qp.x_lo.resize(n);
    qp.x_up.resize(n);
    for (int j = 0; j < n; ++j) {
      const double t = U(rng);
      qp.x_lo[j] = t < 0.2 ? x0[j] : (t < 0.3 ? -kInf : x0[j] - U(rng));
      const double s = U(rng);
      qp.x_up[j] = s < 0.2 ? x0[j] : (s < 0.3 ? kInf : x0[j] + U(rng));
    }
  }
  return qp;
}


/// An orthonormal n x r matrix (QR of a Gaussian one).
inline MatrixXd orthonormal(std::mt19937& rng, int n, int r) {
  std::normal_distribution<double> N(0.0, 1.0);
  MatrixXd M(n, r);
  for (Eigen::Index i = 0; i < M.size(); ++i) M.data()[i] = N(rng);
  Eigen::HouseholderQR<MatrixXd> qr(M);
  return qr.householderQ() * MatrixXd::Identity(n, r);
}

/// A QP and its answer, known by construction.
struct KnownQp {
  DenseQp qp;
  VectorXd x, y_eq, y_in, y_box;  // the optimum and its multipliers (unique)
  double objective = 0.0;
};

/// A convex QP with a rank-r Hessian H = V diag(s) V' (r < n allowed, r = 0 is a linear program; eigenvalues s in
/// [0.1, 10] on its range, exactly 0 on the other n - r directions up to the rounding of the product) plus
/// rel_reg * max(H_ii) * I, and a unique optimum known in advance: x* and multipliers y* are drawn first, then
/// n - r + {0, 1, 2} linearly independent constraints are made active at x* (equalities, rows at their lower or
/// upper bound, box bounds), their multipliers strictly signed, and g = A_eq' y_eq + C' y_in + y_box - H x*
/// (stationarity). The active normals leave no direction of the null space of H free, so x* is the only
/// minimiser; the other rows and bounds are slack at x*.
inline KnownQp knownAnswer(std::mt19937& rng, int n, int r, double rel_reg = 0.0) {
  std::normal_distribution<double> N(0.0, 1.0);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  KnownQp k;
  DenseQp& qp = k.qp;
  const MatrixXd V = orthonormal(rng, n, n);
  VectorXd s(n);
  for (int i = 0; i < n; ++i) s[i] = i < r ? std::pow(10.0, 2.0 * U(rng) - 1.0) : 0.0;
  qp.H = V * s.asDiagonal() * V.transpose();
  qp.H = (0.5 * (qp.H + qp.H.transpose())).eval();
  if (rel_reg > 0.0) qp.H += rel_reg * qp.H.diagonal().maxCoeff() * MatrixXd::Identity(n, n);
  k.x.resize(n);
  for (int j = 0; j < n; ++j) k.x[j] = N(rng);
  const VectorXd& xs = k.x;
  const int active = std::min(n, n - r + static_cast<int>(3.0 * U(rng)));
  // Active constraints: kinds 0 equality, 1 row at its lower bound, 2 row at its upper bound, 3 box bound.
  const bool box = U(rng) < 0.5;
  std::vector<int> kind(active);
  std::vector<int> box_of(active, -1);
  std::vector<int> coords(n);
  for (int j = 0; j < n; ++j) coords[j] = j;
  std::shuffle(coords.begin(), coords.end(), rng);
  int m_eq = 0, m_act = 0, n_box_act = 0;
  for (int i = 0; i < active; ++i) {
    kind[i] = static_cast<int>(U(rng) * (box ? 4.0 : 3.0));
    if (kind[i] == 3) box_of[i] = coords[n_box_act++];
    m_eq += kind[i] == 0;
    m_act += kind[i] == 1 || kind[i] == 2;
  }
  const int m_slack = static_cast<int>(U(rng) * 2 * n);
  qp.A_eq.resize(m_eq, n);
  qp.b_eq.resize(m_eq);
  qp.C.resize(m_act + m_slack, n);
  qp.c_lo.resize(m_act + m_slack);
  qp.c_up.resize(m_act + m_slack);
  k.y_eq.setZero(m_eq);
  k.y_in.setZero(m_act + m_slack);
  k.y_box.setZero(box ? n : 0);
  if (box) {
    qp.x_lo.resize(n);
    qp.x_up.resize(n);
    for (int j = 0; j < n; ++j) {  // slack unless made active below
      qp.x_lo[j] = U(rng) < 0.2 ? -kInf : xs[j] - 0.1 - U(rng);
      qp.x_up[j] = U(rng) < 0.2 ? kInf : xs[j] + 0.1 + U(rng);
    }
  }
  VectorXd Ny = VectorXd::Zero(n);  // A_eq' y_eq + C' y_in + y_box
  int ie = 0, ic = 0;
  for (int i = 0; i < active; ++i) {
    VectorXd a(n);
    for (int j = 0; j < n; ++j) a[j] = N(rng);
    const double y = 0.1 + U(rng);  // strictly positive magnitude: strict complementarity
    if (kind[i] == 0) {
      qp.A_eq.row(ie) = a.transpose();
      qp.b_eq[ie] = a.dot(xs);
      k.y_eq[ie] = N(rng);
      Ny += k.y_eq[ie++] * a;
    } else if (kind[i] == 3) {
      const int j = box_of[i];
      const bool lower = U(rng) < 0.5;
      (lower ? qp.x_lo[j] : qp.x_up[j]) = xs[j];
      k.y_box[j] = lower ? y : -y;
      Ny[j] += k.y_box[j];
    } else {
      const bool lower = kind[i] == 1;
      qp.C.row(ic) = a.transpose();
      const double c = a.dot(xs);
      qp.c_lo[ic] = lower ? c : (U(rng) < 0.5 ? -kInf : c - 0.1 - U(rng));
      qp.c_up[ic] = lower ? (U(rng) < 0.5 ? kInf : c + 0.1 + U(rng)) : c;
      k.y_in[ic] = lower ? y : -y;
      Ny += k.y_in[ic++] * a;
    }
  }
  for (int i = ic; i < m_act + m_slack; ++i) {
    for (int j = 0; j < n; ++j) qp.C(i, j) = N(rng);
    const double c = qp.C.row(i).dot(xs);
    qp.c_lo[i] = U(rng) < 0.2 ? -kInf : c - 0.1 - U(rng);
    qp.c_up[i] = U(rng) < 0.2 ? kInf : c + 0.1 + U(rng);
  }
  qp.g = Ny - qp.H * xs;
  k.objective = qp.objective(xs);
  return k;
}

/// A convex QP unbounded below, with its ray known by construction: H of rank r < n, d a unit vector of its null
/// space with g'd < 0, a feasible point x0, and every constraint satisfied along x0 + t d for all t >= 0 (equality
/// rows orthogonal to d; a row or bound is finite only on the side d moves away from, rows orthogonal to d may be
/// two-sided). Then f(x0 + t d) = f(x0) + t g'd -> -inf. With `blocked`, two-sided rows -1 <= v'(x - x0) <= 1
/// for every null-space direction v of H bound the problem (then it has an optimum).
inline DenseQp unboundedQp(std::mt19937& rng, int n, int r, bool blocked, VectorXd* ray = nullptr) {
  std::normal_distribution<double> N(0.0, 1.0);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  DenseQp qp;
  const MatrixXd V = orthonormal(rng, n, n);
  VectorXd s(n);
  for (int i = 0; i < n; ++i) s[i] = i < r ? std::pow(10.0, 2.0 * U(rng) - 1.0) : 0.0;
  qp.H = V * s.asDiagonal() * V.transpose();
  qp.H = (0.5 * (qp.H + qp.H.transpose())).eval();
  VectorXd d = VectorXd::Zero(n);
  for (int i = r; i < n; ++i) d += N(rng) * V.col(i);
  d.normalize();
  VectorXd x0(n);
  qp.g.resize(n);
  for (int j = 0; j < n; ++j) {
    x0[j] = N(rng);
    qp.g[j] = N(rng);
  }
  qp.g -= (qp.g.dot(d) + 1.0 + U(rng)) * d;  // g'd = -(1 + U)
  const int m_eq = static_cast<int>(U(rng) * (n - 1));
  qp.A_eq.resize(m_eq, n);
  for (int i = 0; i < m_eq; ++i) {
    VectorXd a(n);
    for (int j = 0; j < n; ++j) a[j] = N(rng);
    qp.A_eq.row(i) = (a - a.dot(d) * d).transpose();
  }
  qp.b_eq = qp.A_eq * x0;
  const int m_in = static_cast<int>(U(rng) * 2 * n);
  const int m_block = blocked ? n - r : 0;
  qp.C.resize(m_in + m_block, n);
  qp.c_lo.resize(m_in + m_block);
  qp.c_up.resize(m_in + m_block);
  for (int i = 0; i < m_in; ++i) {
    VectorXd c(n);
    for (int j = 0; j < n; ++j) c[j] = N(rng);
    if (U(rng) < 0.2) c -= c.dot(d) * d;  // orthogonal to d: may be two-sided
    const double cx = c.dot(x0), cd = c.dot(d);
    const double lo = U(rng) < 0.3 ? cx : cx - U(rng), up = U(rng) < 0.3 ? cx : cx + U(rng);
    const bool orth = std::abs(cd) < 1e-12;
    qp.C.row(i) = c.transpose();
    qp.c_lo[i] = orth || cd > 0.0 ? lo : -kInf;
    qp.c_up[i] = orth || cd < 0.0 ? up : kInf;
  }
  for (int i = 0; i < m_block; ++i) {
    const VectorXd v = V.col(r + i);
    qp.C.row(m_in + i) = v.transpose();
    qp.c_lo[m_in + i] = v.dot(x0) - 1.0;
    qp.c_up[m_in + i] = v.dot(x0) + 1.0;
  }
  if (U(rng) < 0.5) {
    qp.x_lo.resize(n);
    qp.x_up.resize(n);
    for (int j = 0; j < n; ++j) {
      qp.x_lo[j] = d[j] >= 0.0 ? x0[j] - U(rng) : -kInf;
      qp.x_up[j] = d[j] <= 0.0 ? x0[j] + U(rng) : kInf;
    }
  }
  if (ray) *ray = d;
  return qp;
}

}  // namespace centaur::test
