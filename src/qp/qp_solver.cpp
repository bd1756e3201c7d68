// QpSolver: sizes, validation, the factorisation of H and its singularity test, the unconstrained fast path, the
// KKT check behind every "optimal" and the refinement of x and u on an active set. The dual method itself is in
// qp_dual_method.cpp, the proximal-point iterations for a singular H in qp_proximal.cpp.
#include "qp/qp_solver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Cholesky>

namespace centaur {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

bool noNaN(const Eigen::Ref<const Eigen::VectorXd>& v) {
  for (Eigen::Index i = 0; i < v.size(); ++i)
    if (std::isnan(v[i])) return false;
  return true;
}

}  // namespace

const char* toString(QpStatus status) {
  switch (status) {
    case QpStatus::kOptimal: return "optimal";
    case QpStatus::kInfeasible: return "infeasible";
    case QpStatus::kIterationLimit: return "iteration limit";
    case QpStatus::kInvalidInput: return "invalid input";
    case QpStatus::kNotPositiveDefinite: return "Hessian not positive definite";
    case QpStatus::kUnbounded: return "unbounded";
    case QpStatus::kInaccurate: return "inaccurate (KKT check failed)";
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
  hx_.setZero(n_);
  res_.setZero(n_);
  w_.setZero(n_);
  xk_.setZero(n_);
  gk_.setZero(n_);
  ray_.setZero(n_);
  xb_.setZero(n_);
  ub_.setZero(n_ + 1);
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
  shift_ = 0.0;
  status_ = QpStatus::kInvalidInput;
}

void QpSolver::applyH(const Eigen::VectorXd& v, Eigen::VectorXd& out) const {
  out.head(n_).noalias() = (*H_) * v.head(n_);
  if (shift_ != 0.0) out.head(n_) += shift_ * v.head(n_);
}

bool QpSolver::factorize(double shift) {
  shift_ = shift;
  Eigen::Ref<Eigen::MatrixXd> L = L_.topLeftCorner(n_, n_);
  L = *H_;
  if (shift != 0.0) L.diagonal().array() += shift;
  Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>> llt(L);  // in place (lower triangle): no allocation
  return llt.info() == Eigen::Success;
}

void QpSolver::solveWithFactor(Eigen::VectorXd& v) const {
  const auto L = L_.topLeftCorner(n_, n_).triangularView<Eigen::Lower>();
  auto x = v.head(n_);
  L.solveInPlace(x);
  L.transpose().solveInPlace(x);
}

bool QpSolver::unconstrainedMinimiserIsFeasible(int n_box, bool warm) {
  // Fast path of a solve without equalities and without a warm-start active set: x = -H^-1 g from the Cholesky
  // factor (two triangular solves, no inverse). If it is stationary to the KKT tolerance (else one step of
  // iterative refinement) and violates no row or bound (the main loop's test), it is the optimum with all
  // multipliers zero: exactly where the dual method would stop at its first check.
  if (m_eq_ > 0 || (warm && n_prev_ > 0)) return false;
  for (int i = 0; i < m_in_; ++i)
    if ((*c_lo_)[i] == (*c_up_)[i]) return false;
  for (int j = 0; j < n_box; ++j)
    if ((*x_lo_)[j] == (*x_up_)[j]) return false;
  auto x = x_.head(n_);
  x = -(*g_);
  solveWithFactor(x_);
  for (int pass = 0;; ++pass) {
    applyH(x_, hx_);
    auto r = res_.head(n_);
    r = hx_.head(n_) + *g_;
    const double scale = std::max(hx_.head(n_).cwiseAbs().maxCoeff(), g_->cwiseAbs().maxCoeff());
    if (r.cwiseAbs().maxCoeff() <= settings_.kkt_tol * scale) break;
    if (pass == 1) return false;
    solveWithFactor(res_);
    x -= r;
  }
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
  n_eq_active_ = 0;
  return true;
}

QpStatus QpSolver::solve(const Eigen::Ref<const Eigen::MatrixXd>& H, const Eigen::Ref<const Eigen::VectorXd>& g,
                         const Eigen::Ref<const Eigen::MatrixXd>& A_eq, const Eigen::Ref<const Eigen::VectorXd>& b_eq,
                         const Eigen::Ref<const Eigen::MatrixXd>& C, const Eigen::Ref<const Eigen::VectorXd>& c_lo,
                         const Eigen::Ref<const Eigen::VectorXd>& c_up, const Eigen::Ref<const Eigen::VectorXd>& x_lo,
                         const Eigen::Ref<const Eigen::VectorXd>& x_up) {
  iterations_ = 0;
  prox_iterations_ = 0;
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
  // The previous optimum (same size) is the first centre of proximal iterations, should they be needed.
  if (status_ == QpStatus::kOptimal && prev_n_ == n && settings_.warm_start) {
    xk_.head(n) = x_.head(n);
  } else {
    xk_.head(n).setZero();
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
  y_eq_.setZero();
  y_in_.setZero();
  y_box_.setZero();
  ray_.setZero();

  // Bounds that no point can satisfy.
  for (int i = 0; i < m_in; ++i) {
    if (c_lo[i] > c_up[i] || c_lo[i] == kInf || c_up[i] == -kInf) return fail(QpStatus::kInfeasible);
    row_norm_[i] = C.row(i).norm();
  }
  const int n_box = box ? n : 0;
  for (int j = 0; j < n_box; ++j)
    if (x_lo[j] > x_up[j] || x_lo[j] == kInf || x_up[j] == -kInf) return fail(QpStatus::kInfeasible);

  // ---- H positive definite (pivots above singular_tol * max_i H_ii): the dual method on H itself ----
  h_scale_ = n > 0 ? H.diagonal().maxCoeff() : 0.0;
  if (n > 0 && H.diagonal().minCoeff() < 0.0) return fail(QpStatus::kNotPositiveDefinite);
  max_it_ = settings_.max_iterations > 0 ? settings_.max_iterations : 10 * (n + m_eq + m_in) + 50;
  QpStatus status = QpStatus::kInaccurate;
  if (factorize(0.0)) {
    const double pivot = n > 0 ? L_.diagonal().head(n).cwiseAbs2().minCoeff() : kInf;
    if (pivot > settings_.singular_tol * h_scale_) {
      status = solveDual(settings_.warm_start);
      // Infeasibility is concluded from a linear dependence measured in the metric of H, which a condition number
      // beyond that of the proximal iterations distorts: let them confirm it.
      if (status == QpStatus::kInfeasible && pivot < settings_.proximal_rho * h_scale_) status = QpStatus::kInaccurate;
    }
  }
  // ---- singular, or too ill-conditioned for the KKT check: proximal-point iterations ----
  if (status == QpStatus::kInaccurate) status = solveProximal(g);
  if (status != QpStatus::kOptimal) return fail(status);

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
  rememberActiveSet();
  objective_ = 0.5 * x_.head(n).dot(hx_.head(n)) + g.dot(x_.head(n));  // hx_ = H x from the KKT check
  return status_ = QpStatus::kOptimal;
}

QpStatus QpSolver::fail(QpStatus status) {
  n_prev_ = 0;
  shift_ = 0.0;
  return status_ = status;
}

void QpSolver::rememberActiveSet() {
  n_prev_ = 0;
  for (int k = n_eq_active_; k < iq_; ++k)
    if (!is_eq_[k]) prev_active_[n_prev_++] = active_[k];
  prev_n_ = n_;
  prev_m_eq_ = m_eq_;
  prev_m_in_ = m_in_;
  prev_box_ = has_box_;
}

bool QpSolver::kktHolds() {
  // Stationarity: r = (H + shift) x + g - sum_k u_k n_k against the size of its terms (a normwise backward
  // error: the rounding of H x grows with ||H|| ||x||); dual signs; primal feasibility of every row and bound, the
  // active ones within tolerance of their bound on both sides.
  const double tol = settings_.kkt_tol;
  const int n = n_;
  const double x_max = n > 0 ? x_.head(n).cwiseAbs().maxCoeff() : 0.0;
  applyH(x_, hx_);
  auto r = res_.head(n);
  r = hx_.head(n) + *g_;
  double scale = n > 0 ? std::max({hx_.head(n).cwiseAbs().maxCoeff(), (h_scale_ + shift_) * x_max,
                                   g_->cwiseAbs().maxCoeff()})
                       : 0.0;
  double wrong_sign = 0.0;
  for (int k = 0; k < iq_; ++k) {
    const int id = active_[k];
    const double norm = id < m_eq_ ? A_eq_->row(id).norm() : normalNorm(id);
    addNormal(id, -u_[k], res_);
    scale = std::max(scale, std::abs(u_[k]) * norm);
    if (!is_eq_[k]) wrong_sign = std::max(wrong_sign, -u_[k] * norm);
  }
  if (n > 0 && !(r.cwiseAbs().maxCoeff() <= tol * scale)) return false;  // (also catches NaN)
  if (wrong_sign > tol * scale) return false;
  // Primal: distance (b - n'x) / ||n|| to each bound, relative for large bounds or a large x (the rounding of
  // n'x grows with ||n|| ||x||).
  auto outside = [tol, x_max](double b, double value, double norm, bool two_sided, double sign) {
    if (!(std::abs(b) < kInf)) return false;
    const double nn = norm > 0.0 ? norm : 1.0;
    const double v = sign * (b - value) / nn;
    const double limit = tol * std::max({1.0, std::abs(b) / nn, x_max});
    return two_sided ? !(std::abs(v) <= limit) : !(v <= limit);
  };
  for (int i = 0; i < m_eq_; ++i)
    if (outside((*b_eq_)[i], A_eq_->row(i).dot(x_.head(n)), A_eq_->row(i).norm(), true, 1.0)) return false;
  const int lo0 = m_eq_;
  for (int i = 0; i < m_in_; ++i) {
    const bool eq = (*c_lo_)[i] == (*c_up_)[i];
    if (outside((*c_lo_)[i], cx_[i], row_norm_[i], eq || in_active_[lo0 + 2 * i] == 1, 1.0) ||
        outside((*c_up_)[i], cx_[i], row_norm_[i], eq || in_active_[lo0 + 2 * i + 1] == 1, -1.0))
      return false;
  }
  if (!has_box_) return true;
  const int b0 = m_eq_ + 2 * m_in_;
  for (int j = 0; j < n; ++j) {
    const bool eq = (*x_lo_)[j] == (*x_up_)[j];
    if (outside((*x_lo_)[j], x_[j], 1.0, eq || in_active_[b0 + 2 * j] == 1, 1.0) ||
        outside((*x_up_)[j], x_[j], 1.0, eq || in_active_[b0 + 2 * j + 1] == 1, -1.0))
      return false;
  }
  return true;
}

void QpSolver::refine() {
  // x and u solved afresh from the factorisation of the final active set (instead of accumulated steps), then one
  // step of iterative refinement with the exact residuals: (H + shift) dx - N du = -r_s, N' dx = b_A - N'x, which
  // is the same system with g := r_s. An inequality multiplier that turns out negative is dropped (and the main
  // loop resumes from this dual feasible point).
  for (;;) {
    recomputePrimalDual();
    applyH(x_, hx_);
    res_.head(n_) = hx_.head(n_) + *g_;
    for (int k = 0; k < iq_; ++k) {
      addNormal(active_[k], -u_[k], res_);
      tmp_[k] = rhs(active_[k]) - normalDot(active_[k], x_);
    }
    activeSetSolve(res_.head(n_), w_, r_);
    x_.head(n_) += w_.head(n_);
    u_.head(iq_) += r_.head(iq_);
    const int worst = mostNegativeMultiplier();
    if (worst < 0) return;
    dropFromActiveSet(worst);
  }
}

}  // namespace centaur
