// Step acceptance of the interior-point method: fraction to the boundary, Ipopt's filter line search with
// second-order corrections and its watchdog, and a feasibility restoration when the step size falls below its
// minimum.
#include <algorithm>
#include <cmath>
#include <limits>

#include "ocp_solver/ipm_state.hpp"

namespace centaur::ocp_solver::detail {

namespace {
constexpr double kGammaTheta = 1e-5, kGammaPhi = 1e-8, kDelta = 1.0, kSTheta = 1.1, kSPhi = 2.3, kEtaPhi = 1e-8;
constexpr double kGammaAlpha = 0.05, kKappaSoc = 0.99;
constexpr int kMaxSoc = 4;
constexpr int kWatchdogTrigger = 10, kWatchdogTrials = 3;  // Ipopt's watchdog_shortened_iter_trigger, _trial_iter_max
constexpr double kEps = std::numeric_limits<double>::epsilon();
}  // namespace

double Ipm::maxStep(const Vec& v, const Vec& dv, const Vec& lo, const Vec& hi, const std::vector<char>& has_lo,
                    const std::vector<char>& has_hi, double tau) const {
  double a = 1.0;
  for (int i = 0; i < v.size(); ++i) {
    if (has_lo[i] && dv[i] < 0.0) a = std::min(a, -tau * (v[i] - lo[i]) / dv[i]);
    if (has_hi[i] && dv[i] > 0.0) a = std::min(a, tau * (hi[i] - v[i]) / dv[i]);
  }
  return a;
}

double Ipm::maxDualStep(const Direction& d, double tau) const {
  double a = 1.0;
  auto upd = [&](const Vec& z, const Vec& dz, const std::vector<char>& has) {
    for (int i = 0; i < z.size(); ++i)
      if (has[i] && dz[i] < 0.0) a = std::min(a, -tau * z[i] / dz[i]);
  };
  upd(zl_, d.zl, has_xl_);
  upd(zu_, d.zu, has_xu_);
  upd(vl_, d.vl, has_gl_);
  upd(vu_, d.vu, has_gu_);
  return a;
}

// In Ipopt's order: theta_max, the test against the current point, then the filter, which notes why a trial was
// rejected for its reset heuristic (Filter::accepted).
int Ipm::acceptance(double theta_t, double phi_t, double alpha, double gpd, double theta0, double phi0) {
  if (!std::isfinite(phi_t) || !filter_.belowThetaMax(theta_t)) return 0;
  const double tol = 10.0 * kEps * std::abs(phi0);
  const bool switching = theta0 <= theta_min_ && gpd < 0.0 &&
                         alpha * std::pow(-gpd, kSPhi) > kDelta * std::pow(theta0, kSTheta);
  int type = 0;
  if (switching) {
    type = phi_t - phi0 - kEtaPhi * alpha * gpd <= tol ? 1 : 0;
  } else {
    type = (theta_t <= (1.0 - kGammaTheta) * theta0 || phi_t - (phi0 - kGammaPhi * theta0) <= tol) ? 2 : 0;
  }
  if (type == 0) {
    filter_.rejectedByCurrentPoint();
    return 0;
  }
  if (!filter_.notDominated(theta_t, phi_t)) {
    filter_.rejectedByFilter();
    return 0;
  }
  if (filter_.accepted()) ++stats_.filter_resets;
  return type;
}

bool Ipm::trialPoint(const Direction& d, double alpha) {
  x_trial_ = x_ + alpha * d.x;
  s_trial_ = s_ + alpha * d.s;
  g_trial_.resize(m_);
  return evalFunctions(x_trial_, f_trial_, g_trial_);
}

void Ipm::acceptStep(const Direction& d, double alpha_primal, double alpha_dual) {
  x_ = x_trial_;
  s_ = s_trial_;
  f_ = f_trial_;
  g_ = g_trial_;
  y_ += alpha_primal * d.y;
  zl_ += alpha_dual * d.zl;
  zu_ += alpha_dual * d.zu;
  vl_ += alpha_dual * d.vl;
  vu_ += alpha_dual * d.vu;
  alpha_primal_ = alpha_primal;
  alpha_dual_ = alpha_dual;
  safeguardMultipliers();
  primalResidual(g_, s_, rp_);
}

// Up to kMaxSoc corrections of the rejected first trial: the same matrix with the constraint residual
// accumulated along the step (Ipopt's c_soc = alpha c(x) + c(x_trial)).
bool Ipm::secondOrderCorrection(double alpha, double gpd, double theta0, double phi0, double theta_t) {
  Vec rp_t, c_soc;
  primalResidual(g_trial_, s_trial_, rp_t);
  c_soc = alpha * rp_ + rp_t;
  double theta_old = theta_t;
  Direction d;
  for (int p = 0; p < kMaxSoc; ++p) {
    solveAndRecover(c_soc, d);
    const double a = std::min(maxStep(x_, d.x, xl_, xu_, has_xl_, has_xu_, tau_),
                              maxStep(s_, d.s, gl_, gu_, has_gl_, has_gu_, tau_));
    if (!trialPoint(d, a)) return false;
    const double th = theta(g_trial_, s_trial_);
    const int acc = acceptance(th, barrierObjective(f_trial_, x_trial_, s_trial_), alpha, gpd, theta0, phi0);
    if (acc) {
      if (acc == 2) filter_.add((1.0 - kGammaTheta) * theta0, phi0 - kGammaPhi * theta0);
      d_ = d;
      acceptStep(d, a, maxDualStep(d, tau_));
      ls_type_ = acc == 1 ? 'F' : 'H';
      return true;
    }
    if (th > kKappaSoc * theta_old) return false;
    theta_old = th;
    primalResidual(g_trial_, s_trial_, rp_t);
    c_soc = a * c_soc + rp_t;
  }
  return false;
}

bool Ipm::backtrack(double alpha, double a_dual, double gpd, double theta0, double phi0, bool allow_soc) {
  double a_min = kGammaTheta;
  if (gpd < 0.0) {
    a_min = std::min(kGammaTheta, kGammaPhi * theta0 / -gpd);
    if (theta0 <= theta_min_) a_min = std::min(a_min, kDelta * std::pow(theta0, kSTheta) / std::pow(-gpd, kSPhi));
  }
  a_min *= kGammaAlpha;
  for (;;) {
    if (trialPoint(d_, alpha)) {
      const double th = theta(g_trial_, s_trial_);
      const int acc = acceptance(th, barrierObjective(f_trial_, x_trial_, s_trial_), alpha, gpd, theta0, phi0);
      if (acc) {
        if (acc == 2) filter_.add((1.0 - kGammaTheta) * theta0, phi0 - kGammaPhi * theta0);
        acceptStep(d_, alpha, a_dual);
        ls_type_ = acc == 1 ? 'f' : 'h';
        return true;
      }
      if (allow_soc && ls_trials_ == 0 && th >= theta0 && secondOrderCorrection(alpha, gpd, theta0, phi0, th))
        return true;
    }
    ++ls_trials_;
    alpha *= 0.5;
    if (alpha < a_min) return false;
  }
}

bool Ipm::lineSearch() {
  if (mu_ != wd_.mu) {  // a new barrier problem: the watchdog starts over
    wd_.active = false;
    wd_.shortened = 0;
    wd_.mu = mu_;
  }
  Vec gx, gs;
  barrierGradient(mu_, gx, gs);
  const double gpd = gx.dot(d_.x) + gs.dot(d_.s);
  const double theta0 = theta(g_, s_), phi0 = barrierObjective(f_, x_, s_);
  const double a_max = std::min(maxStep(x_, d_.x, xl_, xu_, has_xl_, has_xu_, tau_),
                                maxStep(s_, d_.s, gl_, gu_, has_gl_, has_gu_, tau_));
  const double a_dual = maxDualStep(d_, tau_);
  ls_trials_ = 0;
  // Tiny step: take it whole and let the barrier parameter decrease.
  double rel = 0.0;
  for (int i = 0; i < n_; ++i) rel = std::max(rel, std::abs(d_.x[i]) / (1.0 + std::abs(x_[i])));
  for (int r = 0; r < m_; ++r) rel = std::max(rel, std::abs(d_.s[r]) / (1.0 + std::abs(s_[r])));
  if (rel < 10.0 * kEps) {
    if (wd_.active) {  // as Ipopt: back to where the watchdog started, and search from there
      stopWatchdog();
      const bool ok = backtrack(wd_.alpha_test, maxDualStep(d_, tau_), wd_.gpd, wd_.theta, wd_.phi, false);
      if (ok) wd_.shortened = ls_trials_ > 0 ? 1 : 0;
      return ok;
    }
    if (!trialPoint(d_, a_max)) return false;
    acceptStep(d_, a_max, a_dual);
    tiny_step_ = true;
    ls_type_ = 't';
    return true;
  }
  if (!wd_.active && wd_.shortened >= kWatchdogTrigger) {
    wd_ = Watchdog{true, 0, 0, mu_, x_, s_, y_, zl_, zu_, vl_, vu_, g_, rp_, f_, theta0, phi0, gpd, a_max, d_};
    ++stats_.watchdog_starts;
  }
  if (wd_.active) return watchdogStep(a_max, a_dual);
  const bool ok = backtrack(a_max, a_dual, gpd, theta0, phi0, true);
  if (ok) wd_.shortened = ls_trials_ > 0 ? wd_.shortened + 1 : 0;
  return ok;
}

// One watchdog iteration: the full step, acceptable against the point where the watchdog started (Ipopt tests it
// with that point's step size for the Armijo condition); otherwise taken anyway, up to kWatchdogTrials times, and
// then the method returns to that point and backtracks along its direction (from half its first step).
bool Ipm::watchdogStep(double a_max, double a_dual) {
  const bool evaluated = trialPoint(d_, a_max);
  if (evaluated) {
    const double th = theta(g_trial_, s_trial_);
    const int acc = acceptance(th, barrierObjective(f_trial_, x_trial_, s_trial_), wd_.alpha_test, wd_.gpd,
                               wd_.theta, wd_.phi);
    if (acc) {
      if (acc == 2) filter_.add((1.0 - kGammaTheta) * wd_.theta, wd_.phi - kGammaPhi * wd_.theta);
      acceptStep(d_, a_max, a_dual);
      wd_.active = false;
      wd_.shortened = 0;
      ls_type_ = 'W';
      return true;
    }
  }
  if (evaluated && ++wd_.trials <= kWatchdogTrials) {
    acceptStep(d_, a_max, a_dual);
    ls_type_ = 'w';
    return true;
  }
  stopWatchdog();
  ls_trials_ = 1;
  const bool ok = backtrack(0.5 * wd_.alpha_test, maxDualStep(d_, tau_), wd_.gpd, wd_.theta, wd_.phi, false);
  if (ok) wd_.shortened = ls_trials_ > 1 ? 1 : 0;
  return ok;
}

// Back to the point where the watchdog started, with its direction (and its derivatives, which the next
// iteration or a restoration reads).
void Ipm::stopWatchdog() {
  ++stats_.watchdog_returns;
  wd_.active = false;
  wd_.shortened = 0;
  x_ = wd_.x;
  s_ = wd_.s;
  y_ = wd_.y;
  zl_ = wd_.zl;
  zu_ = wd_.zu;
  vl_ = wd_.vl;
  vu_ = wd_.vu;
  f_ = wd_.f;
  g_ = wd_.g;
  rp_ = wd_.rp;
  d_ = wd_.d;
  evalDerivatives();
}

// Feasibility restoration: minimum-norm steps towards the linearized constraints,
//   min 1/2 zeta |D_R (x - x_R)|^2 + barrier  s.t.  J dx - ds = -c,
// (zeta = sqrt(mu), D_R = 1 / max(1, |x_R|)) with a backtracking on theta, until theta has dropped to 0.9 of
// its value at the start and the point is acceptable to the filter of the original problem.
bool Ipm::restoration() {
  wd_.shortened = 0;  // as Ipopt's: the watchdog counts the shortened steps after a restoration afresh
  const double theta_r = theta(g_, s_), zeta = std::sqrt(mu_);
  const Vec x_r = x_;
  const Vec grad_saved = grad_, y_saved = y_;
  extra_diag_.resize(n_);
  for (int i = 0; i < n_; ++i) extra_diag_[i] = zeta / std::max(1.0, x_r[i] * x_r[i]);
  hess_in_use_ = zero_hess_.data();
  bool ok = false;
  for (int it = 0; it < 50 && !ok; ++it) {
    ++stats_.restoration_iterations;
    grad_ = extra_diag_.cwiseProduct(x_ - x_r);
    y_.setZero(m_);
    if (!factorWithCorrection()) break;
    solveAndRecover(rp_, d_);
    const double th0 = theta(g_, s_);
    const double a_max = std::min(maxStep(x_, d_.x, xl_, xu_, has_xl_, has_xu_, tau_),
                                  maxStep(s_, d_.s, gl_, gu_, has_gl_, has_gu_, tau_));
    double a = a_max;
    bool stepped = false;
    for (int t = 0; t < 30; ++t, a *= 0.5) {
      if (trialPoint(d_, a) && theta(g_trial_, s_trial_) <= (1.0 - 1e-4 * a) * th0) {
        stepped = true;
        break;
      }
    }
    if (!stepped) break;
    const Vec y_keep = y_;
    acceptStep(d_, a, maxDualStep(d_, tau_));
    y_ = y_keep;
    const double th = theta(g_, s_);
    ok = th <= 0.9 * theta_r && filter_.acceptable(th, barrierObjective(f_, x_, s_));
    if (!ok && !evalDerivatives()) break;
  }
  extra_diag_.resize(0);
  hess_in_use_ = nullptr;
  ls_type_ = 'r';
  if (!ok) {
    grad_ = grad_saved;
    y_ = y_saved;
    return false;
  }
  y_.setZero(m_);
  if (!evalDerivatives()) return false;
  leastSquaresMultipliers();
  return true;
}

}  // namespace centaur::ocp_solver::detail
