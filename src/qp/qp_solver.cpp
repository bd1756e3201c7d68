#include "qp/qp_solver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

// Goldfarb & Idnani, "A numerically stable dual method for solving strictly convex quadratic programs",
// Math. Programming 27 (1983). Notation: H = L L' (Cholesky, once per solve), N_A the active normals,
// J = L^-T Q and R from the QR factorisation L^-1 N_A = Q [R; 0]; then J' H J = I and J' N_A = [R; 0].
// With J = [J1 J2] (J1: the first iq columns), for a new normal n and d = J'n = [d1; d2]:
//   primal step direction z = J2 d2 (keeps the active constraints, increases n'x at rate ||d2||^2),
//   dual step direction   r = R^-1 d1 (how the active multipliers change per unit multiplier of n).
// Adding/dropping a constraint updates J and R with Givens rotations, O(n^2) each.

namespace centaur {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

bool noNaN(const Eigen::Ref<const Eigen::VectorXd>& v) {
  for (Eigen::Index i = 0; i < v.size(); ++i)
    if (std::isnan(v[i])) return false;
  return true;
}

// Givens rotation (c, s) with c a + s b = h = hypot(a, b) and -s a + c b = 0.
inline void givens(double a, double b, double& c, double& s, double& h) {
  h = std::sqrt(a * a + b * b);  // std::hypot is ~10x slower; fall back to it only on over/underflow
  if (!(h > 1e-150 && h < 1e150)) h = std::hypot(a, b);
  if (h == 0.0) {
    c = 1.0;
    s = 0.0;
  } else {
    c = a / h;
    s = b / h;
  }
}

// Columns (p, q) of M <- (c p + s q, -s p + c q).
inline void rotateColumns(Eigen::MatrixXd& M, int p, int q, double c, double s, int rows) {
  double* a = M.col(p).data();
  double* b = M.col(q).data();
  for (int k = 0; k < rows; ++k) {
    const double x = a[k], y = b[k];
    a[k] = c * x + s * y;
    b[k] = -s * x + c * y;
  }
}
}  // namespace

const char* toString(QpStatus status) {
  switch (status) {
    case QpStatus::kOptimal: return "optimal";
    case QpStatus::kInfeasible: return "infeasible";
    case QpStatus::kIterationLimit: return "iteration limit";
    case QpStatus::kInvalidInput: return "invalid input";
    case QpStatus::kNotPositiveDefinite: return "Hessian not positive definite";
  }
  return "unknown";
}

void QpSolver::resize(int n, int m_eq_max, int m_in_max) {
  n_max_ = std::max(n, 0);
  n_ = n_max_;
  m_eq_max_ = std::max(m_eq_max, 0);
  m_in_max_ = std::max(m_in_max, 0);
  L_.setZero(n_, n_);
  J_.setZero(n_, n_);
  R_.setZero(n_, n_);
  d_.setZero(n_);
  z_.setZero(n_);
  r_.setZero(n_ + 1);
  u_.setZero(n_ + 1);
  x_.setZero(n_);
  tmp_.setZero(std::max(n_, m_in_max_));
  row_norm_.setZero(m_in_max_);
  cx_.setZero(m_in_max_);
  y_eq_.setZero(m_eq_max_);
  y_in_.setZero(m_in_max_);
  y_box_.setZero(n_);
  active_.assign(n_ + 1, -1);
  is_eq_.assign(n_ + 1, 0);
  in_active_.assign(m_eq_max_ + 2 * m_in_max_ + 2 * n_, 0);
  prev_active_.assign(n_ + 1, -1);
  n_prev_ = 0;
  iq_ = 0;
  status_ = QpStatus::kInvalidInput;
}

double QpSolver::normalDot(int id, const Eigen::VectorXd& v) const {
  if (id < m_eq_) return A_eq_->row(id).dot(v.head(n_));
  id -= m_eq_;
  if (id < 2 * m_in_) {
    const double d = C_->row(id / 2).dot(v.head(n_));
    return (id % 2) ? -d : d;
  }
  id -= 2 * m_in_;
  return (id % 2) ? -v[id / 2] : v[id / 2];
}

double QpSolver::rhs(int id) const {
  if (id < m_eq_) return (*b_eq_)[id];
  id -= m_eq_;
  if (id < 2 * m_in_) return (id % 2) ? -(*c_up_)[id / 2] : (*c_lo_)[id / 2];
  id -= 2 * m_in_;
  return (id % 2) ? -(*x_up_)[id / 2] : (*x_lo_)[id / 2];
}

double QpSolver::normalNorm(int id) const {
  if (id < m_eq_) return 1.0;  // unused for equalities
  id -= m_eq_;
  if (id < 2 * m_in_) return row_norm_[id / 2];
  return 1.0;
}

void QpSolver::computeD(int id) {
  if (id < m_eq_) {
    tmp_.head(n_) = A_eq_->row(id).transpose();
    d_.head(n_).noalias() = J_.topLeftCorner(n_, n_).transpose() * tmp_.head(n_);
    return;
  }
  int k = id - m_eq_;
  if (k < 2 * m_in_) {
    tmp_.head(n_) = C_->row(k / 2).transpose();
    d_.head(n_).noalias() = J_.topLeftCorner(n_, n_).transpose() * tmp_.head(n_);
    if (k % 2) d_.head(n_) = -d_.head(n_);
    return;
  }
  k -= 2 * m_in_;
  d_.head(n_) = J_.row(k / 2).head(n_).transpose();
  if (k % 2) d_.head(n_) = -d_.head(n_);
}

bool QpSolver::isDependent() const {
  if (iq_ >= n_) return true;
  const double tail = d_.segment(iq_, n_ - iq_).norm();
  return !(tail > settings_.dependency_tol * d_.head(n_).norm());
}

void QpSolver::computeStep() {
  const int k = n_ - iq_;
  if (k > 0) {
    z_.head(n_).noalias() = J_.block(0, iq_, n_, k) * d_.segment(iq_, k);
  } else {
    z_.head(n_).setZero();
  }
  if (iq_ > 0) {
    auto r = r_.head(iq_);
    r = d_.head(iq_);
    R_.topLeftCorner(iq_, iq_).triangularView<Eigen::Upper>().solveInPlace(r);
  }
}

void QpSolver::addToActiveSet(int id, bool equality) {
  // Rotate d_ (and J's columns) so that d_[iq+1..n) = 0; the new column of R is d_[0..iq].
  for (int j = n_ - 1; j > iq_; --j) {
    if (d_[j] == 0.0) continue;
    double c, s, h;
    givens(d_[j - 1], d_[j], c, s, h);
    d_[j - 1] = h;
    d_[j] = 0.0;
    rotateColumns(J_, j - 1, j, c, s, n_);
  }
  R_.col(iq_).head(iq_ + 1) = d_.head(iq_ + 1);
  active_[iq_] = id;
  is_eq_[iq_] = equality ? 1 : 0;
  in_active_[id] = 1;
  ++iq_;
}

void QpSolver::dropFromActiveSet(int pos) {
  in_active_[active_[pos]] = 0;
  for (int k = pos; k + 1 < iq_; ++k) {
    active_[k] = active_[k + 1];
    is_eq_[k] = is_eq_[k + 1];
    u_[k] = u_[k + 1];
    R_.col(k).head(k + 2) = R_.col(k + 1).head(k + 2);
  }
  --iq_;
  // R is now upper Hessenberg from column pos on: rotate rows (k, k+1) to clear R(k+1, k).
  for (int k = pos; k < iq_; ++k) {
    double c, s, h;
    givens(R_(k, k), R_(k + 1, k), c, s, h);
    R_(k, k) = h;
    R_(k + 1, k) = 0.0;
    for (int j = k + 1; j < iq_; ++j) {
      const double a = R_(k, j), b = R_(k + 1, j);
      R_(k, j) = c * a + s * b;
      R_(k + 1, j) = -s * a + c * b;
    }
    rotateColumns(J_, k, k + 1, c, s, n_);
  }
  R_.col(iq_).head(iq_ + 1).setZero();
}

void QpSolver::recomputePrimalDual() {
  // x = J1 R^-T b_A - J2 J2' g ;  u = R^-1 (R^-T b_A + J1' g).
  auto y1 = tmp_.head(iq_);
  for (int k = 0; k < iq_; ++k) y1[k] = rhs(active_[k]);
  if (iq_ > 0) R_.topLeftCorner(iq_, iq_).transpose().triangularView<Eigen::Lower>().solveInPlace(y1);
  d_.head(n_).noalias() = J_.topLeftCorner(n_, n_).transpose() * (*g_);
  z_.head(iq_) = y1;
  z_.segment(iq_, n_ - iq_) = -d_.segment(iq_, n_ - iq_);
  x_.head(n_).noalias() = J_.topLeftCorner(n_, n_) * z_.head(n_);
  if (iq_ > 0) {
    auto u = u_.head(iq_);
    u = y1 + d_.head(iq_);
    R_.topLeftCorner(iq_, iq_).triangularView<Eigen::Upper>().solveInPlace(u);
  }
}

void QpSolver::restoreDualFeasibility() {
  // x := minimiser on the active set; drop the most negative inequality multiplier until none is left.
  for (;;) {
    recomputePrimalDual();
    int worst = -1;
    double most_negative = 0.0;
    for (int k = 0; k < iq_; ++k)
      if (!is_eq_[k] && u_[k] < most_negative) {
        most_negative = u_[k];
        worst = k;
      }
    if (worst < 0) return;
    dropFromActiveSet(worst);
  }
}

bool QpSolver::unconstrainedMinimiserIsFeasible(const Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>>& llt, int n_box) {
  // Fast path of a solve without equalities and without a warm-start active set: x = -H^-1 g from the Cholesky
  // factor (two triangular solves, no inverse). If it violates no row or bound (the main loop's test), it is the
  // optimum with all multipliers zero: exactly where the dual method would stop at its first check.
  if (m_eq_ > 0 || (settings_.warm_start && n_prev_ > 0)) return false;
  for (int i = 0; i < m_in_; ++i)
    if ((*c_lo_)[i] == (*c_up_)[i]) return false;
  for (int j = 0; j < n_box; ++j)
    if ((*x_lo_)[j] == (*x_up_)[j]) return false;
  auto x = x_.head(n_);
  x = -(*g_);
  llt.solveInPlace(x);
  const double ftol = settings_.feasibility_tol;
  auto violated = [ftol](double b, double value, double norm, double sign) {
    if (!(std::abs(b) < kInf)) return false;
    const double v = sign * (b - value) / norm;
    return v > ftol * std::max(1.0, std::abs(b) / norm);
  };
  if (m_in_ > 0) cx_.head(m_in_).noalias() = (*C_) * x;
  for (int i = 0; i < m_in_; ++i)
    if (violated((*c_lo_)[i], cx_[i], row_norm_[i], 1.0) || violated((*c_up_)[i], cx_[i], row_norm_[i], -1.0))
      return false;
  for (int j = 0; j < n_box; ++j)
    if (violated((*x_lo_)[j], x[j], 1.0, 1.0) || violated((*x_up_)[j], x[j], 1.0, -1.0)) return false;
  iq_ = 0;
  n_prev_ = 0;
  prev_n_ = n_;
  prev_m_eq_ = m_eq_;
  prev_m_in_ = m_in_;
  prev_box_ = has_box_;
  tmp_.head(n_).noalias() = (*H_) * x;
  objective_ = 0.5 * x.dot(tmp_.head(n_)) + g_->dot(x);
  return true;
}

QpStatus QpSolver::solve(const Eigen::Ref<const Eigen::MatrixXd>& H, const Eigen::Ref<const Eigen::VectorXd>& g,
                         const Eigen::Ref<const Eigen::MatrixXd>& A_eq, const Eigen::Ref<const Eigen::VectorXd>& b_eq,
                         const Eigen::Ref<const Eigen::MatrixXd>& C, const Eigen::Ref<const Eigen::VectorXd>& c_lo,
                         const Eigen::Ref<const Eigen::VectorXd>& c_up, const Eigen::Ref<const Eigen::VectorXd>& x_lo,
                         const Eigen::Ref<const Eigen::VectorXd>& x_up) {
  iterations_ = 0;
  iq_ = 0;
  objective_ = kInf;
  // ---- validate ----
  const int n = static_cast<int>(H.rows());
  const int m_eq = static_cast<int>(A_eq.rows());
  const int m_in = static_cast<int>(C.rows());
  const bool box = x_lo.size() > 0 || x_up.size() > 0;
  if (n > n_max_ || H.cols() != n || g.size() != n || m_eq > m_eq_max_ || (m_eq > 0 && A_eq.cols() != n) ||
      b_eq.size() != m_eq || m_in > m_in_max_ || (m_in > 0 && C.cols() != n) || c_lo.size() != m_in ||
      c_up.size() != m_in || (box && (x_lo.size() != n || x_up.size() != n))) {
    n_prev_ = 0;
    return status_ = QpStatus::kInvalidInput;
  }
  // A sum is NaN/Inf iff an entry is (or, harmlessly, if the entries overflow it: |values| ~ 1e307).
  auto finite = [](const auto& m) { return m.size() == 0 || std::isfinite(m.sum()); };
  if (!finite(H) || !finite(g) || !finite(A_eq) || !finite(b_eq) || !finite(C) ||
      !noNaN(c_lo) || !noNaN(c_up) || (box && (!noNaN(x_lo) || !noNaN(x_up)))) {
    n_prev_ = 0;
    return status_ = QpStatus::kInvalidInput;
  }
  n_ = n;
  m_eq_ = m_eq;
  m_in_ = m_in;
  has_box_ = box;
  A_eq_ = &A_eq;
  b_eq_ = &b_eq;
  C_ = &C;
  c_lo_ = &c_lo;
  c_up_ = &c_up;
  x_lo_ = &x_lo;
  x_up_ = &x_up;
  g_ = &g;
  H_ = &H;
  const int n_box = box ? n : 0;
  const int n_ids = m_eq + 2 * m_in + 2 * n_box;
  std::fill(in_active_.begin(), in_active_.begin() + n_ids, 0);
  y_eq_.setZero();
  y_in_.setZero();
  y_box_.setZero();

  // Bounds that no point can satisfy.
  for (int i = 0; i < m_in; ++i) {
    if (c_lo[i] > c_up[i] || c_lo[i] == kInf || c_up[i] == -kInf) return status_ = QpStatus::kInfeasible;
    row_norm_[i] = C.row(i).norm();
  }
  for (int j = 0; j < n_box; ++j)
    if (x_lo[j] > x_up[j] || x_lo[j] == kInf || x_up[j] == -kInf) return status_ = QpStatus::kInfeasible;

  // ---- factorise H = L L', J = L^-T ----
  Eigen::Ref<Eigen::MatrixXd> L = L_.topLeftCorner(n, n);
  L = H;
  Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>> llt(L);  // in place: no allocation
  if (llt.info() != Eigen::Success) {
    n_prev_ = 0;
    return status_ = QpStatus::kNotPositiveDefinite;
  }
  if (unconstrainedMinimiserIsFeasible(llt, n_box)) return status_ = QpStatus::kOptimal;
  Eigen::Ref<Eigen::MatrixXd> J = J_.topLeftCorner(n, n);
  J.setIdentity();
  llt.matrixU().solveInPlace(J);
  R_.topLeftCorner(n, n).setZero();

  // ---- equalities: A_eq rows, C rows with c_lo == c_up, box with x_lo == x_up ----
  auto addEquality = [&](int id) {
    computeD(id);
    if (!isDependent()) addToActiveSet(id, true);  // dependent ones are checked for consistency below
  };
  for (int i = 0; i < m_eq; ++i) addEquality(i);
  for (int i = 0; i < m_in; ++i)
    if (c_lo[i] == c_up[i]) addEquality(m_eq + 2 * i);
  for (int j = 0; j < n_box; ++j)
    if (x_lo[j] == x_up[j]) addEquality(m_eq + 2 * m_in + 2 * j);
  recomputePrimalDual();
  auto inconsistent = [&](int id) {
    if (in_active_[id]) return false;
    const double b = rhs(id);
    const double res = std::abs(normalDot(id, x_) - b);
    return res > 1e3 * settings_.feasibility_tol * std::max(1.0, std::abs(b));
  };
  for (int i = 0; i < m_eq; ++i)
    if (inconsistent(i)) return status_ = QpStatus::kInfeasible;
  // Consistent dependent equality rows of C / the box are marked (2) so that the main loop never picks them.
  for (int i = 0; i < m_in; ++i) {
    const int id = m_eq + 2 * i;
    if (c_lo[i] != c_up[i] || in_active_[id]) continue;
    if (inconsistent(id)) return status_ = QpStatus::kInfeasible;
    in_active_[id] = 2;
  }
  for (int j = 0; j < n_box; ++j) {
    const int id = m_eq + 2 * m_in + 2 * j;
    if (x_lo[j] != x_up[j] || in_active_[id]) continue;
    if (inconsistent(id)) return status_ = QpStatus::kInfeasible;
    in_active_[id] = 2;
  }
  const int n_eq_active = iq_;

  // ---- warm start: re-impose the previous active inequalities, then restore dual feasibility ----
  if (settings_.warm_start && n_prev_ > 0 && prev_n_ == n && prev_m_eq_ == m_eq && prev_m_in_ == m_in && prev_box_ == box) {
    for (int k = 0; k < n_prev_; ++k) {
      const int id = prev_active_[k];
      if (id < m_eq || id >= n_ids) continue;
      const int base = (id - m_eq) & ~1;  // the two sides of one row share the base id
      if (in_active_[m_eq + base] || in_active_[m_eq + base + 1]) continue;
      if (!(std::abs(rhs(id)) < kInf)) continue;
      computeD(id);
      if (!isDependent()) addToActiveSet(id, false);
    }
    if (iq_ > n_eq_active) restoreDualFeasibility();
  }
  n_prev_ = 0;

  // ---- main loop of the dual method ----
  const int max_it = settings_.max_iterations > 0 ? settings_.max_iterations : 10 * (n + m_eq + m_in) + 50;
  for (;;) {
    // Most violated constraint (distance to its hyperplane, relative for large bounds).
    int p = -1;
    double worst = 0.0;
    const double ftol = settings_.feasibility_tol;
    auto consider = [&](int id, double b, double value, double norm, double sign) {
      if (!(std::abs(b) < kInf)) return;
      const double v = sign * (b - value) / norm;
      if (v > worst && v > ftol * std::max(1.0, std::abs(b) / norm)) {
        worst = v;
        p = id;
      }
    };
    if (m_in > 0) cx_.head(m_in).noalias() = C * x_.head(n);
    for (int i = 0; i < m_in; ++i) {
      const int id = m_eq + 2 * i;
      if (in_active_[id] || in_active_[id + 1]) continue;  // a side is active (or the row is settled)
      consider(id, c_lo[i], cx_[i], row_norm_[i], 1.0);
      consider(id + 1, c_up[i], cx_[i], row_norm_[i], -1.0);
    }
    for (int j = 0; j < n_box; ++j) {
      const int id = m_eq + 2 * m_in + 2 * j;
      if (in_active_[id] || in_active_[id + 1]) continue;
      consider(id, x_lo[j], x_[j], 1.0, 1.0);
      consider(id + 1, x_up[j], x_[j], 1.0, -1.0);
    }
    if (p < 0) break;

    double u_plus = 0.0;
    for (;;) {
      if (iterations_ >= max_it) return status_ = QpStatus::kIterationLimit;
      computeD(p);
      const bool dependent = isDependent();
      computeStep();
      // Partial (dual) step: largest t keeping the active inequality multipliers >= 0.
      double t1 = kInf;
      int l = -1;
      for (int k = 0; k < iq_; ++k) {
        if (is_eq_[k] || !(r_[k] > 0.0)) continue;
        const double ratio = u_[k] / r_[k];
        if (ratio < t1) {
          t1 = ratio;
          l = k;
        }
      }
      // Full (primal) step: makes constraint p active.
      double t2 = kInf;
      if (!dependent) {
        const double s = rhs(p) - normalDot(p, x_);
        t2 = std::max(0.0, s) / d_.segment(iq_, n_ - iq_).squaredNorm();
      }
      const double t = std::min(t1, t2);
      if (t == kInf) {
        const double b = rhs(p);
        const double nn = normalNorm(p);
        const double v = (b - normalDot(p, x_)) / nn;
        if (v > settings_.infeasibility_tol * std::max(1.0, std::abs(b) / nn)) return status_ = QpStatus::kInfeasible;
        in_active_[p] = 3;  // a rounding-level violation of a degenerate constraint: ignored in this solve
        restoreDualFeasibility();
        break;
      }
      ++iterations_;
      if (t2 == kInf) {  // dual step only
        u_.head(iq_) -= t * r_.head(iq_);
        u_plus += t;
        dropFromActiveSet(l);
        continue;
      }
      x_.head(n) += t * z_.head(n);
      u_.head(iq_) -= t * r_.head(iq_);
      u_plus += t;
      if (t2 <= t1) {
        u_[iq_] = u_plus;
        addToActiveSet(p, false);  // d_ is still J'n_p of the current J
        break;
      }
      dropFromActiveSet(l);
    }
  }

  // ---- results ----
  for (int k = 0; k < iq_; ++k) {
    int id = active_[k];
    const double u = u_[k];
    if (id < m_eq) {
      y_eq_[id] = u;
      continue;
    }
    id -= m_eq;
    if (id < 2 * m_in) {
      y_in_[id / 2] += (id % 2) ? -u : u;
      continue;
    }
    id -= 2 * m_in;
    y_box_[id / 2] += (id % 2) ? -u : u;
  }
  n_prev_ = 0;
  for (int k = n_eq_active; k < iq_; ++k)
    if (!is_eq_[k]) prev_active_[n_prev_++] = active_[k];
  prev_n_ = n;
  prev_m_eq_ = m_eq;
  prev_m_in_ = m_in;
  prev_box_ = box;
  tmp_.head(n).noalias() = H * x_.head(n);
  objective_ = 0.5 * x_.head(n).dot(tmp_.head(n)) + g.dot(x_.head(n));
  return status_ = QpStatus::kOptimal;
}

}  // namespace centaur
