// The barrier parameter of the interior-point method.
//   monotone: Fiacco-McCormick, mu decreases when the barrier problem is solved to kappa_eps * mu.
//   adaptive (Ipopt's default strategy, Nocedal, Waechter & Waltz 2009): in "free mode" mu is chosen every
//     iteration: the affine-scaling step (mu = 0) and the centring step (mu = average complementarity) are
//     solved with the same factorization, and sigma = mu / average complementarity minimizes a quality function
//     (the linearized KKT error after the step, fraction to the boundary included) by golden-section search
//     in sigma (not log sigma: Ipopt's search is linear too); the step for that mu is their combination (the
//     right-hand side is affine in mu). Free-mode iterates must make progress in a filter of (constraint
//     violation, objective); otherwise the method falls back to the monotone mode, from 0.8 x the average
//     complementarity, until an iterate is acceptable again.
#include <algorithm>
#include <cmath>
#include <limits>

#include "ocp_solver/ipm_state.hpp"

namespace centaur::ocp_solver::detail {

namespace {
constexpr double kKappaEps = 10.0;  // barrier subproblem tolerance factor
constexpr double kKappaMu = 0.2, kThetaMu = 1.5, kTauMin = 0.99;
constexpr double kSigmaMax = 100.0, kMuMin = 1e-11, kMuMaxFact = 1e3, kMonotoneInitFactor = 0.8;
constexpr double kFilterMarginFact = 1e-5;
constexpr int kGoldenSteps = 8;
constexpr double kSigmaMin = 1e-6, kSectionTol = 1e-2, kOneMinusEps = 1e-4;

// Golden-section minimization of q over [lo, hi] (ends included in the candidates).
template <class Q>
double goldenSection(const Q& q, double lo, double hi) {
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  const double q_lo = q(lo), q_hi = q(hi);
  double a = hi - g * (hi - lo), b = lo + g * (hi - lo);
  double qa = q(a), qb = q(b);
  for (int it = 0; it < kGoldenSteps && hi - lo >= kSectionTol * hi; ++it) {
    if (qa < qb) {
      hi = b, b = a, qb = qa;
      a = hi - g * (hi - lo);
      qa = q(a);
    } else {
      lo = a, a = b, qa = qb;
      b = lo + g * (hi - lo);
      qb = q(b);
    }
  }
  double best = qa < qb ? a : b, q_best = std::min(qa, qb);
  if (q_lo < q_best) best = lo, q_best = q_lo;
  if (q_hi < q_best) best = hi;
  return best;
}
}  // namespace

double Ipm::averageComplementarity() const {
  double sum = 0.0;
  int count = 0;
  for (int i = 0; i < n_; ++i) {
    if (has_xl_[i]) sum += (x_[i] - xl_[i]) * zl_[i], ++count;
    if (has_xu_[i]) sum += (xu_[i] - x_[i]) * zu_[i], ++count;
  }
  for (int r = 0; r < m_; ++r) {
    if (has_gl_[r]) sum += (s_[r] - gl_[r]) * vl_[r], ++count;
    if (has_gu_[r]) sum += (gu_[r] - s_[r]) * vu_[r], ++count;
  }
  return count ? sum / count : 0.0;
}

void Ipm::monotoneUpdate() {
  const double mu_min = adaptive_ ? kMuMin : opt_.tol / 10.0;
  bool changed = false;
  while (mu_ > mu_min && (tiny_step_ || optimalityError(mu_).scaled() <= kKappaEps * mu_)) {
    mu_ = std::max(mu_min, std::min(kKappaMu * mu_, std::pow(mu_, kThetaMu)));
    tau_ = std::max(kTauMin, 1.0 - mu_);
    changed = true;
    tiny_step_ = false;
  }
  tiny_step_ = false;
  if (changed) filter_.reset(filter_.thetaMax());
}

bool Ipm::progressAcceptable() const {
  const double th = theta(g_, s_);
  const double margin = kFilterMarginFact * std::min(1.0, std::max(std::abs(f_), th));
  return progress_filter_.acceptable(th + margin, f_ + margin);
}

void Ipm::rememberProgress() {
  const double th = theta(g_, s_);
  const double margin = kFilterMarginFact * std::min(1.0, std::max(std::abs(f_), th));
  progress_filter_.add(th - margin, f_ - margin);
}

void Ipm::enterMonotoneMode() {
  free_mode_ = false;
  ++stats_.mode_switches;
  mu_ = std::max(kMuMin, std::min(mu_max_, kMonotoneInitFactor * averageComplementarity()));
  tau_ = std::max(kTauMin, 1.0 - mu_);
  filter_.reset(filter_.thetaMax());
}

// Called before the direction: monotone updates, or the adaptive mode switches.
void Ipm::updateBarrier() {
  if (!adaptive_ || averageComplementarity() <= 0.0) {
    adaptive_ = false;
    monotoneUpdate();
    return;
  }
  if (mu_max_ == 0.0) mu_max_ = kMuMaxFact * averageComplementarity();
  if (free_mode_) {
    if (stats_.iterations > 0 && !progressAcceptable()) {  // no progress: fixed (monotone) mode
      enterMonotoneMode();
      return;
    }
    rememberProgress();
    return;
  }
  if (progressAcceptable()) {  // progress again: back to free mode
    free_mode_ = true;
    rememberProgress();
    return;
  }
  monotoneUpdate();
}

void Ipm::combine(const Direction& a, const Direction& c, double sigma, Direction& d) const {
  d.x = a.x + sigma * (c.x - a.x);
  d.s = a.s + sigma * (c.s - a.s);
  d.y = a.y + sigma * (c.y - a.y);
  d.zl = a.zl + sigma * (c.zl - a.zl);
  d.zu = a.zu + sigma * (c.zu - a.zu);
  d.vl = a.vl + sigma * (c.vl - a.vl);
  d.vu = a.vu + sigma * (c.vu - a.vu);
}

// The parts of the quality function that do not depend on sigma: the dual infeasibility (its squared sum and
// count) and the mean squared primal infeasibility, computed once per iteration.
Ipm::QualityBase Ipm::qualityBase() const {
  QualityBase b;
  const SparsePattern& p = nlp_.pattern();
  Vec rd = grad_ - zl_ + zu_;
  for (std::size_t t = 0; t < p.jac_rows.size(); ++t) rd[p.jac_cols[t]] += jac_[t] * y_[p.jac_rows[t]];
  for (int i = 0; i < n_; ++i) {
    if (fixed_[i]) continue;
    b.dual += rd[i] * rd[i], ++b.nd;
  }
  for (int r = 0; r < m_; ++r) {
    if (!ineq_[r]) continue;
    const double rs = -y_[r] - vl_[r] + vu_[r];
    b.dual += rs * rs, ++b.nd;
  }
  b.primal = m_ ? rp_.squaredNorm() / m_ : 0.0;
  return b;
}

// The bounded components of the two steps, laid out for qualityFunction(), which runs for ~12 values of sigma per
// iteration: contiguous, with the upper bounds' signs folded in, so that its loops have no indirection and one case.
// Negating a step, and subtracting 0, are exact, so every value below is bit for bit that of the plain formulas.
void Ipm::qualityTerms(const Direction& a, const Direction& c, QualityTerms& t) const {
  struct Family {
    const std::vector<int>& idx;
    const Vec &v, &lo, &hi, &zl, &zu;
    const std::vector<char> &has_lo, &has_hi;
    const Vec &av, &cv, &azl, &czl, &azu, &czu;
  };
  const Family fams[2] = {{x_bounded_, x_, xl_, xu_, zl_, zu_, has_xl_, has_xu_, a.x, c.x, a.zl, c.zl, a.zu, c.zu},
                          {s_bounded_, s_, gl_, gu_, vl_, vu_, has_gl_, has_gu_, a.s, c.s, a.vl, c.vl, a.vu, c.vu}};
  for (std::vector<double>* v : {&t.gap, &t.b0, &t.b1, &t.sav, &t.sdv, &t.z, &t.az, &t.dzd}) v->clear();
  const auto add = [&t](double gap, double b0, double b1, double sav, double sdv, double z, double az, double dzd) {
    t.gap.push_back(gap), t.b0.push_back(b0), t.b1.push_back(b1), t.sav.push_back(sav), t.sdv.push_back(sdv);
    t.z.push_back(z), t.az.push_back(az), t.dzd.push_back(dzd);
  };
  for (const Family& f : fams) {
    for (int i : f.idx) {
      const double av = f.av[i], dv = f.cv[i] - f.av[i];
      if (f.has_lo[i]) add(f.v[i] - f.lo[i], f.v[i], f.lo[i], av, dv, f.zl[i], f.azl[i], f.czl[i] - f.azl[i]);
      if (f.has_hi[i]) add(f.hi[i] - f.v[i], f.hi[i] - f.v[i], 0.0, -av, -dv, f.zu[i], f.azu[i], f.czu[i] - f.azu[i]);
    }
  }
}

// Ipopt's quality function (2-norm squared, each part divided by its size) of the linearized KKT error after the
// step for sigma with the fraction-to-the-boundary step sizes. Only the bounded components enter, so it reads
// those of the combined step (the same values as combine()) without forming it: the same result as the step
// rules of the line search on the combined step, in two passes.
double Ipm::qualityFunction(const QualityTerms& t, double sigma, double tau, const QualityBase& base) const {
  const int n = static_cast<int>(t.gap.size());
  const double *gap = t.gap.data(), *sav = t.sav.data(), *sdv = t.sdv.data();
  const double *z = t.z.data(), *az = t.az.data(), *dzd = t.dzd.data();
  double ap = 1.0, ad = 1.0;  // as maxStep and maxDualStep (a minimum does not depend on the order)
  for (int e = 0; e < n; ++e) {
    const double dv = sav[e] + sigma * sdv[e], dz = az[e] + sigma * dzd[e];
    if (dv < 0.0) ap = std::min(ap, -tau * gap[e] / dv);
    if (dz < 0.0) ad = std::min(ad, -tau * z[e] / dz);
  }
  const double *b0 = t.b0.data(), *b1 = t.b1.data();
  double compl_sq = 0.0;
  for (int e = 0; e < n; ++e) {
    const double w = (b0[e] + ap * (sav[e] + sigma * sdv[e]) - b1[e]) * (z[e] + ad * (az[e] + sigma * dzd[e]));
    compl_sq += w * w;
  }
  return (1.0 - ad) * (1.0 - ad) * base.dual / std::max(1, base.nd) + (1.0 - ap) * (1.0 - ap) * base.primal +
         compl_sq / std::max(1, n);
}

bool Ipm::adaptiveDirection() {
  const double avg = averageComplementarity();
  solveAffineAndCentring(avg);
  if (!aff_.x.allFinite() || !cen_.x.allFinite()) return false;
  // Minimize the quality function over sigma in [sigma_lo, sigma_up]: the side of sigma = 1 where it decreases
  // is chosen first (from q(1) and q(1 - eps)), then a golden-section search in sigma on that side, stopped when
  // the bracket is narrower than kSectionTol relative to its upper end or after kGoldenSteps sections.
  const double sigma_lo = std::max(kSigmaMin, kMuMin / avg), sigma_up = std::max(sigma_lo, std::min(kSigmaMax, mu_max_ / avg));
  const QualityBase base = qualityBase();
  // The fraction to the boundary of the free mode, as Ipopt's: from the NLP error, not from mu (which the quality
  // function may set to its floor while the iterate is still far from optimal; 1 - mu would then let a step go to
  // within mu of the bounds). The quality function uses it too.
  const double tau = std::max(kTauMin, 1.0 - nlp_error_);
  qualityTerms(aff_, cen_, quality_terms_);
  auto q = [&](double sg) { return qualityFunction(quality_terms_, sg, tau, base); };
  double sigma;
  if (sigma_up <= 1.0 || sigma_lo >= 1.0) {
    sigma = goldenSection(q, sigma_lo, sigma_up);
  } else {
    const double q1 = q(1.0), q1m = q(1.0 - kOneMinusEps);
    sigma = q1m < q1 ? goldenSection(q, sigma_lo, 1.0) : goldenSection(q, 1.0, sigma_up);
  }
  mu_ = std::clamp(sigma * avg, kMuMin, mu_max_);
  sigma = mu_ / avg;
  tau_ = tau;
  combine(aff_, cen_, sigma, d_);
  filter_.reset(filter_.thetaMax());  // the barrier problem changed
  return d_.x.allFinite() && d_.y.allFinite();
}

}  // namespace centaur::ocp_solver::detail
