// The Newton step of the interior-point method: inertia correction (Ipopt's Algorithm IC) and the recovery of
// the slack and bound-multiplier steps from the reduced system.
#include <algorithm>
#include <cmath>

#include "ocp_solver/ipm_state.hpp"

namespace centaur::ocp_solver::detail {

namespace {
constexpr double kDeltaW0 = 1e-4, kDeltaWMin = 1e-20, kDeltaWMax = 1e20;
constexpr double kKappaWMinus = 1.0 / 3.0, kKappaWPlus = 8.0, kKappaWPlusBar = 100.0;
constexpr double kDeltaC = 1e-8, kKappaC = 0.25;
constexpr double kFarAboveLast = 1e5;  // Ipopt: a trial this far above the last delta_w grows by kKappaWPlusBar
constexpr int kDegenIters = 3;
}  // namespace

// Factor the KKT matrix with the smallest primal regularization delta_w that gives the inertia (n, m, 0);
// dependent rows get the dual regularization delta_c. A failed trial multiplies delta_w by kKappaWPlus, or by
// kKappaWPlusBar when there was no delta_w before or the trial is already kFarAboveLast times the last one (Ipopt's
// rule: a matrix that needs far more than the last iterate's regularization gets there in fewer trials).
// After kDegenIters consecutive iterations that needed a delta_w, the first attempt already uses one (the
// unregularized matrix is then not tried). Ipopt takes this shortcut only when the unregularized matrix was
// singular, not merely of the wrong inertia; the jump OCPs' KKT matrices have the wrong inertia at almost every
// iteration, and always trying the unregularized matrix first took the squat jump from 77 to 971 iterations, so
// ours triggers on the wrong inertia too. When no delta_w up to its maximum gives the inertia, the rows are taken
// as dependent after all, as Ipopt does: delta_c, and delta_w from zero again. On three points of
// docs/planner.md's half-squat-jump grid every delta_w up to 1e20 failed in an early iteration; with delta_c the
// solves go on and converge.
bool Ipm::factorWithCorrection() {
  sigma_s_.setZero(m_);
  for (int r = 0; r < m_; ++r) {
    if (has_gl_[r]) sigma_s_[r] += vl_[r] / (s_[r] - gl_[r]);
    if (has_gu_[r]) sigma_s_[r] += vu_[r] / (gu_[r] - s_[r]);
  }
  Vec sigma_x = Vec::Zero(n_);
  for (int i = 0; i < n_; ++i) {
    if (has_xl_[i]) sigma_x[i] += zl_[i] / (x_[i] - xl_[i]);
    if (has_xu_[i]) sigma_x[i] += zu_[i] / (xu_[i] - x_[i]);
  }
  delta_c_ = 0.0;
  delta_w_ = hess_degenerate_ ? (delta_w_last_ == 0.0 ? kDeltaW0 : std::max(kDeltaWMin, kKappaWMinus * delta_w_last_))
                              : 0.0;
  const auto t = std::chrono::steady_clock::now();
  bool ok = false;
  for (int attempt = 0; attempt < 100; ++attempt) {
    dxdiag_ = sigma_x.array() + delta_w_;
    if (extra_diag_.size() == n_) dxdiag_ += extra_diag_;
    dc_.resize(m_);
    for (int r = 0; r < m_; ++r) dc_[r] = (ineq_[r] ? 1.0 / (sigma_s_[r] + delta_w_) : 0.0) + delta_c_;
    ++stats_.factorizations;
    const double* hess = hess_in_use_ ? hess_in_use_ : hess_.data();
    const KktStatus st = attempt == 0 ? kkt_.factor(hess, jac_.data(), dxdiag_, dc_)
                                      : kkt_.refactor(hess, jac_.data(), dxdiag_, dc_);
    if (st == KktStatus::kOk) {
      ok = true;
      break;
    }
    if (st == KktStatus::kSingular && delta_c_ == 0.0) {
      delta_c_ = kDeltaC * std::pow(mu_, kKappaC);
      continue;
    }
    if (delta_w_ == 0.0) {
      delta_w_ = delta_w_last_ == 0.0 ? kDeltaW0 : std::max(kDeltaWMin, kKappaWMinus * delta_w_last_);
    } else {
      const bool far = delta_w_last_ == 0.0 || delta_w_ > kFarAboveLast * delta_w_last_;
      delta_w_ *= far ? kKappaWPlusBar : kKappaWPlus;
    }
    if (delta_w_ > kDeltaWMax) {
      if (delta_c_ > 0.0) break;
      delta_c_ = kDeltaC * std::pow(mu_, kKappaC);
      delta_w_ = 0.0;
    }
  }
  stats_.time_factor += std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
  if (!ok) return false;
  if (delta_w_ > 0.0) delta_w_last_ = delta_w_;
  if (!hess_degenerate_) {
    degen_iters_ = delta_w_ > 0.0 ? degen_iters_ + 1 : 0;
    hess_degenerate_ = degen_iters_ >= kDegenIters;
  }
  return true;
}

// Right-hand side of the reduced system for the primal residual `rp` (the current one, or the accumulated
// one of a second-order correction) and the barrier parameter mu.
void Ipm::assembleRhs(const Vec& rp, double mu, StepRhs& rhs) const {
  Vec gx, gs;
  barrierGradient(mu, gx, gs);
  const SparsePattern& p = nlp_.pattern();
  rhs.mu = mu;
  rhs.rx = -gx;
  for (std::size_t t = 0; t < p.jac_rows.size(); ++t) rhs.rx[p.jac_cols[t]] -= jac_[t] * y_[p.jac_rows[t]];
  for (int i = 0; i < n_; ++i)
    if (fixed_[i]) rhs.rx[i] = 0.0;
  rhs.rho_s.setZero(m_);
  rhs.rc.resize(m_);
  for (int r = 0; r < m_; ++r) {
    rhs.rc[r] = -rp[r];
    if (ineq_[r]) {
      rhs.rho_s[r] = y_[r] - gs[r];
      rhs.rc[r] += rhs.rho_s[r] / (sigma_s_[r] + delta_w_);
    }
  }
}

void Ipm::recover(const StepRhs& rhs, Direction& d) const {
  const double mu = rhs.mu;
  d.s.setZero(m_);
  d.vl.setZero(m_);
  d.vu.setZero(m_);
  for (int r = 0; r < m_; ++r) {
    if (!ineq_[r]) continue;
    d.s[r] = (rhs.rho_s[r] + d.y[r]) / (sigma_s_[r] + delta_w_);
    if (has_gl_[r]) {
      const double sl = s_[r] - gl_[r];
      d.vl[r] = mu / sl - vl_[r] - vl_[r] / sl * d.s[r];
    }
    if (has_gu_[r]) {
      const double su = gu_[r] - s_[r];
      d.vu[r] = mu / su - vu_[r] + vu_[r] / su * d.s[r];
    }
  }
  d.zl.setZero(n_);
  d.zu.setZero(n_);
  for (int i = 0; i < n_; ++i) {
    if (has_xl_[i]) {
      const double sl = x_[i] - xl_[i];
      d.zl[i] = mu / sl - zl_[i] - zl_[i] / sl * d.x[i];
    }
    if (has_xu_[i]) {
      const double su = xu_[i] - x_[i];
      d.zu[i] = mu / su - zu_[i] + zu_[i] / su * d.x[i];
    }
  }
}

void Ipm::solveAndRecover(const Vec& rp, Direction& d) {
  assembleRhs(rp, mu_, rhs_);
  const auto t = std::chrono::steady_clock::now();
  kkt_.solve(rhs_.rx, rhs_.rc, d.x, d.y);
  stats_.time_solve += std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
  ++stats_.solves;
  recover(rhs_, d);
}

void Ipm::solveAffineAndCentring(double mu_cen) {
  assembleRhs(rp_, 0.0, rhs_);
  assembleRhs(rp_, mu_cen, rhs_cen_);
  const auto t = std::chrono::steady_clock::now();
  kkt_.solveTwo({rhs_.rx, rhs_.rc, aff_.x, aff_.y}, {rhs_cen_.rx, rhs_cen_.rc, cen_.x, cen_.y});
  stats_.time_solve += std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
  stats_.solves += 2;
  recover(rhs_, aff_);
  recover(rhs_cen_, cen_);
}

bool Ipm::computeDirection() {
  if (!factorWithCorrection()) return false;
  if (adaptive_ && free_mode_ && extra_diag_.size() == 0) return adaptiveDirection();
  solveAndRecover(rp_, d_);
  return d_.x.allFinite() && d_.y.allFinite();
}

}  // namespace centaur::ocp_solver::detail
