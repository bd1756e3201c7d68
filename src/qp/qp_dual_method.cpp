// QpSolver: the dual active-set method of Goldfarb & Idnani on the factorisation of H (+ a shift) in L_.
#include <algorithm>
#include <cmath>
#include <limits>

#include "qp/qp_solver.hpp"

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

void QpSolver::addNormal(int id, double scale, Eigen::VectorXd& v) const {
  if (id < m_eq_) {
    v.head(n_) += scale * A_eq_->row(id).transpose();
    return;
  }
  int k = id - m_eq_;
  if (k < 2 * m_in_) {
    v.head(n_) += ((k % 2) ? -scale : scale) * C_->row(k / 2).transpose();
    return;
  }
  k -= 2 * m_in_;
  v[k / 2] += (k % 2) ? -scale : scale;
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

void QpSolver::activeSetSolve(const Eigen::Ref<const Eigen::VectorXd>& gv, Eigen::VectorXd& x_out, Eigen::VectorXd& u_out) {
  // The minimiser of 1/2 x'(H + shift I)x + gv'x with the active constraints at b_A (in tmp_) and its multipliers:
  // x = J1 R^-T b_A - J2 J2' gv ;  u = R^-1 (R^-T b_A + J1' gv).
  auto y1 = tmp_.head(iq_);
  if (iq_ > 0) R_.topLeftCorner(iq_, iq_).transpose().triangularView<Eigen::Lower>().solveInPlace(y1);
  d_.head(n_).noalias() = J_.topLeftCorner(n_, n_).transpose() * gv;
  z_.head(iq_) = y1;
  z_.segment(iq_, n_ - iq_) = -d_.segment(iq_, n_ - iq_);
  x_out.head(n_).noalias() = J_.topLeftCorner(n_, n_) * z_.head(n_);
  if (iq_ > 0) {
    auto u = u_out.head(iq_);
    u = y1 + d_.head(iq_);
    R_.topLeftCorner(iq_, iq_).triangularView<Eigen::Upper>().solveInPlace(u);
  }
}

void QpSolver::recomputePrimalDual() {
  for (int k = 0; k < iq_; ++k) tmp_[k] = rhs(active_[k]);
  activeSetSolve(*g_, x_, u_);
}

int QpSolver::mostNegativeMultiplier() const {
  int worst = -1;
  double most_negative = 0.0;
  for (int k = 0; k < iq_; ++k)
    if (!is_eq_[k] && u_[k] < most_negative) {
      most_negative = u_[k];
      worst = k;
    }
  return worst;
}

void QpSolver::restoreDualFeasibility() {
  // x := minimiser on the active set; drop the most negative inequality multiplier until none is left.
  for (;;) {
    recomputePrimalDual();
    const int worst = mostNegativeMultiplier();
    if (worst < 0) return;
    dropFromActiveSet(worst);
  }
}

QpStatus QpSolver::solveDual(bool warm) {
  // The dual method for H + shift_ I (factor in L_) and *g_.
  const int n = n_, m_eq = m_eq_, m_in = m_in_;
  const int n_box = has_box_ ? n : 0;
  const int n_ids = m_eq + 2 * m_in + 2 * n_box;
  std::fill(in_active_.begin(), in_active_.begin() + n_ids, 0);
  iq_ = 0;
  n_eq_active_ = 0;
  if (unconstrainedMinimiserIsFeasible(n_box, warm)) return QpStatus::kOptimal;
  Eigen::Ref<Eigen::MatrixXd> J = J_.topLeftCorner(n, n);
  J.setIdentity();
  L_.topLeftCorner(n, n).triangularView<Eigen::Lower>().transpose().solveInPlace(J);  // J = L^-T
  R_.topLeftCorner(n, n).setZero();
  const auto& c_lo = *c_lo_;
  const auto& c_up = *c_up_;
  const auto& x_lo = *x_lo_;
  const auto& x_up = *x_up_;

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
  // (relative to a large x too: the rounding of n'x grows with ||n|| ||x||)
  const double x_max = n > 0 ? x_.head(n).cwiseAbs().maxCoeff() : 0.0;
  auto inconsistent = [&](int id) {
    if (in_active_[id]) return false;
    const double b = rhs(id);
    const double res = std::abs(normalDot(id, x_) - b);
    const double norm = id < m_eq ? A_eq_->row(id).norm() : normalNorm(id);
    return res > 1e3 * settings_.feasibility_tol * std::max({1.0, std::abs(b), norm * x_max});
  };
  for (int i = 0; i < m_eq; ++i)
    if (inconsistent(i)) return QpStatus::kInfeasible;
  // Consistent dependent equality rows of C / the box are marked (2) so that the main loop never picks them.
  for (int i = 0; i < m_in; ++i) {
    const int id = m_eq + 2 * i;
    if (c_lo[i] != c_up[i] || in_active_[id]) continue;
    if (inconsistent(id)) return QpStatus::kInfeasible;
    in_active_[id] = 2;
  }
  for (int j = 0; j < n_box; ++j) {
    const int id = m_eq + 2 * m_in + 2 * j;
    if (x_lo[j] != x_up[j] || in_active_[id]) continue;
    if (inconsistent(id)) return QpStatus::kInfeasible;
    in_active_[id] = 2;
  }
  n_eq_active_ = iq_;

  // ---- warm start: re-impose the previous active inequalities, then restore dual feasibility ----
  if (warm && n_prev_ > 0 && prev_n_ == n && prev_m_eq_ == m_eq && prev_m_in_ == m_in && prev_box_ == has_box_) {
    for (int k = 0; k < n_prev_; ++k) {
      const int id = prev_active_[k];
      if (id < m_eq || id >= n_ids) continue;
      const int base = (id - m_eq) & ~1;  // the two sides of one row share the base id
      if (in_active_[m_eq + base] || in_active_[m_eq + base + 1]) continue;
      if (!(std::abs(rhs(id)) < kInf)) continue;
      computeD(id);
      if (!isDependent()) addToActiveSet(id, false);
    }
    if (iq_ > n_eq_active_) restoreDualFeasibility();
  }
  n_prev_ = 0;

  // ---- main loop, then the KKT check (twice more after refining x and u on the final active set) ----
  for (int attempt = 0;; ++attempt) {
    const QpStatus status = dualLoop();
    if (status != QpStatus::kOptimal) return status;
    if (kktHolds()) return QpStatus::kOptimal;
    if (attempt == 2) return QpStatus::kInaccurate;
    refine();
  }
}

// The most violated inactive inequality side at x (distance to its hyperplane, relative for large bounds), -1 if
// none is violated beyond the feasibility tolerance.
int QpSolver::mostViolated() {
  const int n = n_, m_eq = m_eq_, m_in = m_in_;
  const int n_box = has_box_ ? n : 0;
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
  if (m_in > 0) cx_.head(m_in).noalias() = *C_ * x_.head(n);
  for (int i = 0; i < m_in; ++i) {
    const int id = m_eq + 2 * i;
    if (in_active_[id] || in_active_[id + 1]) continue;  // a side is active (or the row is settled)
    consider(id, (*c_lo_)[i], cx_[i], row_norm_[i], 1.0);
    consider(id + 1, (*c_up_)[i], cx_[i], row_norm_[i], -1.0);
  }
  for (int j = 0; j < n_box; ++j) {
    const int id = m_eq + 2 * m_in + 2 * j;
    if (in_active_[id] || in_active_[id + 1]) continue;
    consider(id, (*x_lo_)[j], x_[j], 1.0, 1.0);
    consider(id + 1, (*x_up_)[j], x_[j], 1.0, -1.0);
  }
  return p;
}

QpStatus QpSolver::dualLoop() {
  const int n = n_;
  bool refined = false;
  for (;;) {
    const int p = mostViolated();
    if (p < 0) return QpStatus::kOptimal;  // (subject to the KKT check)

    double u_plus = 0.0;
    for (;;) {
      if (iterations_ >= max_it_) return QpStatus::kIterationLimit;
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
        // p depends on the active normals and no multiplier can be released: infeasible, unless its violation is
        // a rounding artefact. The violation of a combination of active constraints is only as small as their
        // residuals at x: x and u are refined on the active set once before concluding.
        const double b = rhs(p);
        const double nn = normalNorm(p);
        const double v = (b - normalDot(p, x_)) / nn;
        const double x_max = x_.head(n).cwiseAbs().maxCoeff();
        if (v > settings_.infeasibility_tol * std::max({1.0, std::abs(b) / nn, x_max})) {
          if (refined) return QpStatus::kInfeasible;
          refined = true;
          refine();
          break;  // the most violated constraint again, from the refined point
        }
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
}

}  // namespace centaur
