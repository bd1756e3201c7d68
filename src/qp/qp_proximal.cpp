// QpSolver: proximal-point iterations for a singular (or too ill-conditioned) Hessian, the polish of their answer on
// its active set, and the detection of unboundedness.
#include <algorithm>
#include <cmath>
#include <limits>

#include "qp/qp_solver.hpp"

namespace centaur {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

QpStatus QpSolver::solveProximal(const Eigen::Ref<const Eigen::VectorXd>& g) {
  // x_{k+1} = argmin 1/2 x'Hx + g'x + rho/2 ||x - x_k||^2 = the QP with H + rho I and g - rho x_k, same
  // constraints. At a fixed point the KKT conditions of the original problem hold (the stationarity residual of
  // x_{k+1} is -rho (x_{k+1} - x_k)); if there is no optimum because f is unbounded below, the steps tend to a
  // ray of descent, which flatDescent() recognises. Each iteration is warm-started from the previous active set.
  const int n = n_;
  const double rho = settings_.proximal_rho * (h_scale_ > 0.0 ? h_scale_ : 1.0);
  if (!factorize(rho)) return QpStatus::kNotPositiveDefinite;  // an eigenvalue of H below -rho: not convex
  const Eigen::Ref<const Eigen::VectorXd> gk(gk_.head(n));
  if (!settings_.warm_start) n_prev_ = 0;
  for (int k = 0; k < settings_.max_proximal_iterations; ++k) {
    gk_.head(n) = g - rho * xk_.head(n);
    g_ = &gk;
    shift_ = rho;
    const QpStatus status = solveDual(true);
    ++prox_iterations_;
    if (status != QpStatus::kOptimal) return status;
    rememberActiveSet();
    g_ = &g;  // the original problem at x_{k+1}
    if (polishHolds()) return QpStatus::kOptimal;
    w_.head(n) = x_.head(n) - xk_.head(n);
    const double t = k > 0 ? flatDescent(w_) : 0.0;
    if (t == kInf) return QpStatus::kUnbounded;
    // Extrapolation: along a flat descent blocked at distance t the iterations would only creep towards the
    // blocking bound (|g'd| / rho per step); the next centre is on it.
    xk_.head(n) = x_.head(n) + t * ray_.head(n);
  }
  return QpStatus::kIterationLimit;
}

bool QpSolver::polishHolds() {
  // On the active set of the proximal iterate, the KKT system of the original problem (H, not H + rho I) is
  // solved by iterative refinement preconditioned with the factorisation of H + rho I: each step is a proximal
  // iteration that keeps the active set, O(n^2) instead of a QP. It converges to the exact optimum when the
  // active set is the optimal one (and gives an accurate x, not only a point within the KKT tolerance); otherwise
  // the iterate is kept as it was. True if the polished (or, failing that, the plain) iterate passes the KKT check.
  const int n = n_, iq = iq_;
  xb_.head(n) = x_.head(n);
  ub_.head(iq) = u_.head(iq);
  double last = kInf;
  for (int step = 0; step < 50; ++step) {
    shift_ = 0.0;
    applyH(x_, hx_);
    res_.head(n) = hx_.head(n) + *g_;
    for (int k = 0; k < iq; ++k) {
      addNormal(active_[k], -u_[k], res_);
      tmp_[k] = rhs(active_[k]) - normalDot(active_[k], x_);
    }
    const double size = res_.head(n).cwiseAbs().sum() + tmp_.head(iq).cwiseAbs().sum();
    if (!(size < 0.5 * last)) break;  // converged to rounding (or not converging: a different active set)
    last = size;
    shift_ = settings_.proximal_rho * (h_scale_ > 0.0 ? h_scale_ : 1.0);  // the factor's shift
    activeSetSolve(res_.head(n), w_, r_);
    x_.head(n) += w_.head(n);
    u_.head(iq) += r_.head(iq);
  }
  shift_ = 0.0;
  if (m_in_ > 0) cx_.head(m_in_).noalias() = (*C_) * x_.head(n);
  if (kktHolds()) return true;
  x_.head(n) = xb_.head(n);
  u_.head(iq) = ub_.head(iq);
  if (m_in_ > 0) cx_.head(m_in_).noalias() = (*C_) * x_.head(n);
  return kktHolds();
}

double QpSolver::flatDescent(const Eigen::VectorXd& d) {
  // d (the last proximal step, direction ray_ = d / ||d||) is a flat descent when (to the tolerances) H d = 0
  // (curvature below singular_tol, the flatness the singularity test accepts), g'd < 0 and A_eq d = 0. It is a ray
  // of unbounded descent (inf) when x + t d stays feasible for every t >= 0 from the feasible x: every finite bound
  // of a row or variable on the side d moves away from (or d runs along it); else the distance t to the first
  // bound it reaches. 0 when d is not a flat descent.
  const int n = n_;
  const double dn = d.head(n).norm();
  if (!(dn > 0.0) || !std::isfinite(dn)) return 0.0;
  auto w = ray_.head(n);
  w = d.head(n) / dn;
  applyH(ray_, hx_);
  const double flat = settings_.singular_tol * (h_scale_ > 0.0 ? h_scale_ : 1.0);
  if (!(hx_.head(n).norm() <= flat)) return 0.0;
  const double tol = settings_.kkt_tol;
  if (!(g_->dot(w) < -tol * g_->norm())) return 0.0;
  for (int i = 0; i < m_eq_; ++i)
    if (!(std::abs(A_eq_->row(i).dot(w)) <= tol * A_eq_->row(i).norm())) return 0.0;
  double t = kInf;
  auto block = [&t](double slack, double rate) { t = std::min(t, std::max(0.0, slack) / rate); };
  for (int i = 0; i < m_in_; ++i) {
    const double cw = C_->row(i).dot(w), lim = tol * row_norm_[i];
    if (std::isfinite((*c_lo_)[i]) && cw < -lim) block(cx_[i] - (*c_lo_)[i], -cw);
    if (std::isfinite((*c_up_)[i]) && cw > lim) block((*c_up_)[i] - cx_[i], cw);
  }
  if (has_box_)
    for (int j = 0; j < n; ++j) {
      if (std::isfinite((*x_lo_)[j]) && w[j] < -tol) block(x_[j] - (*x_lo_)[j], -w[j]);
      if (std::isfinite((*x_up_)[j]) && w[j] > tol) block((*x_up_)[j] - x_[j], w[j]);
    }
  return t;
}

}  // namespace centaur
