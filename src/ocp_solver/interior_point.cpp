#include "ocp_solver/interior_point.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "ocp_solver/ipm_state.hpp"

namespace centaur::ocp_solver {

const char* toString(IpmStatus s) {
  switch (s) {
    case IpmStatus::kSolved: return "solved";
    case IpmStatus::kAcceptable: return "solved_acceptable";
    case IpmStatus::kMaxIterations: return "max_iterations";
    case IpmStatus::kMaxTime: return "max_cpu_time";
    case IpmStatus::kRestorationFailed: return "restoration_failed";
    case IpmStatus::kInfeasible: return "infeasible";
    case IpmStatus::kNumericalTrouble: return "numerical_trouble";
    case IpmStatus::kEvaluationError: return "evaluation_error";
  }
  return "failed";
}

IpmResult solveInteriorPoint(Nlp& nlp, KktSolver& kkt, const IpmOptions& options, const WarmStart* warm) {
  detail::Ipm ipm(nlp, kkt, options, warm);
  return ipm.run();
}

namespace detail {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kSmax = 100.0;       // Ipopt s_max (scaling of the optimality error)
constexpr double kTauMin = 0.99;
constexpr double kKappaSigma = 1e10;  // bound multiplier safeguard
constexpr double kKappaD = 1e-5;      // linear damping of one-sided bounds
}  // namespace

Ipm::Ipm(Nlp& nlp, KktSolver& kkt, const IpmOptions& opt, const WarmStart* warm)
    : nlp_(nlp), kkt_(kkt), opt_(opt), warm_(warm) {}

double Ipm::elapsed() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count(); }

void Ipm::setupProblem() {
  const SparsePattern& p = nlp_.pattern();
  n_ = p.n;
  m_ = p.m;
  D_ = nlp_.variableScale();
  Vec xl, xu;
  nlp_.bounds(xl, xu, gl_, gu_);
  xl_ = xl.cwiseQuotient(D_);
  xu_ = xu.cwiseQuotient(D_);
  fixed_.assign(n_, 0);
  has_xl_.assign(n_, 0);
  has_xu_.assign(n_, 0);
  for (int i = 0; i < n_; ++i) {
    fixed_[i] = xl[i] == xu[i];
    has_xl_[i] = !fixed_[i] && std::isfinite(xl[i]);
    has_xu_[i] = !fixed_[i] && std::isfinite(xu[i]);
  }
  ineq_.assign(m_, 0);
  has_gl_.assign(m_, 0);
  has_gu_.assign(m_, 0);
  for (int r = 0; r < m_; ++r) {
    ineq_[r] = gl_[r] != gu_[r];
    has_gl_[r] = ineq_[r] && std::isfinite(gl_[r]);
    has_gu_[r] = ineq_[r] && std::isfinite(gu_[r]);
  }
  x_bounded_.clear();
  s_bounded_.clear();
  for (int i = 0; i < n_; ++i)
    if (has_xl_[i] || has_xu_[i]) x_bounded_.push_back(i);
  for (int r = 0; r < m_; ++r)
    if (has_gl_[r] || has_gu_[r]) s_bounded_.push_back(r);
  // As Ipopt: every inequality bound is relaxed by bound_relax_factor * max(1, |bound|) (in the scaled
  // variables), so that the interior is never empty; the final x is projected back (honor_original_bounds).
  xl_orig_ = xl_;
  xu_orig_ = xu_;
  gl_orig_ = gl_;
  gu_orig_ = gu_;
  const double rf = opt_.bound_relax_factor;
  for (int i = 0; i < n_; ++i) {
    if (has_xl_[i]) xl_[i] -= rf * std::max(1.0, std::abs(xl_[i]));
    if (has_xu_[i]) xu_[i] += rf * std::max(1.0, std::abs(xu_[i]));
  }
  for (int r = 0; r < m_; ++r) {
    if (has_gl_[r]) gl_[r] -= rf * std::max(1.0, std::abs(gl_[r]));
    if (has_gu_[r]) gu_[r] += rf * std::max(1.0, std::abs(gu_[r]));
  }
  jac_scale_.resize(p.jac_cols.size());
  for (std::size_t t = 0; t < p.jac_cols.size(); ++t) jac_scale_[t] = D_[p.jac_cols[t]];
  hess_scale_.resize(p.hess_rows.size());
  for (std::size_t t = 0; t < p.hess_rows.size(); ++t) hess_scale_[t] = D_[p.hess_rows[t]] * D_[p.hess_cols[t]];
  jac_.assign(p.jac_rows.size(), 0.0);
  hess_.assign(p.hess_rows.size(), 0.0);
  zero_hess_.assign(p.hess_rows.size(), 0.0);
}

bool Ipm::evalFunctions(const Vec& x, double& f, Vec& g) {
  const auto t = std::chrono::steady_clock::now();
  const Vec xu = unscaled(x);
  const bool ok = nlp_.objective(xu, f) && nlp_.constraints(xu, g) && std::isfinite(f) && g.allFinite();
  stats_.time_functions += std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
  return ok;
}

bool Ipm::evalDerivatives() {
  const auto t = std::chrono::steady_clock::now();
  const bool ok = nlp_.derivatives(unscaled(x_), 1.0, y_, grad_, jac_.data(), hess_.data());
  grad_.array() *= D_.array();
  for (std::size_t k = 0; k < jac_.size(); ++k) jac_[k] *= jac_scale_[k];
  for (std::size_t k = 0; k < hess_.size(); ++k) hess_[k] *= hess_scale_[k];
  stats_.time_derivatives += std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
  if (!ok || !grad_.allFinite()) return false;
  for (double v : jac_)
    if (!std::isfinite(v)) return false;
  for (double v : hess_)
    if (!std::isfinite(v)) return false;
  return true;
}

void Ipm::pushIntoBounds(Vec& v, const Vec& lo, const Vec& hi, const std::vector<char>& has_lo,
                         const std::vector<char>& has_hi, double push, double frac) const {
  for (int i = 0; i < v.size(); ++i) {
    if (has_lo[i] && has_hi[i]) {
      const double pl = std::min(push * std::max(1.0, std::abs(lo[i])), frac * (hi[i] - lo[i]));
      const double pu = std::min(push * std::max(1.0, std::abs(hi[i])), frac * (hi[i] - lo[i]));
      v[i] = std::clamp(v[i], lo[i] + pl, hi[i] - pu);
    } else if (has_lo[i]) {
      v[i] = std::max(v[i], lo[i] + push * std::max(1.0, std::abs(lo[i])));
    } else if (has_hi[i]) {
      v[i] = std::min(v[i], hi[i] - push * std::max(1.0, std::abs(hi[i])));
    }
  }
}

void Ipm::primalResidual(const Vec& g, const Vec& s, Vec& rp) const {
  rp.resize(m_);
  for (int r = 0; r < m_; ++r) rp[r] = ineq_[r] ? g[r] - s[r] : g[r] - gl_[r];
}

double Ipm::theta(const Vec& g, const Vec& s) const {
  double t = 0.0;
  for (int r = 0; r < m_; ++r) t += std::abs(ineq_[r] ? g[r] - s[r] : g[r] - gl_[r]);
  return t;
}

double Ipm::barrierObjective(double f, const Vec& x, const Vec& s) const {
  double phi = f;
  for (int i = 0; i < n_; ++i) {
    if (has_xl_[i]) phi -= mu_ * std::log(x[i] - xl_[i]) - (has_xu_[i] ? 0.0 : kKappaD * mu_ * (x[i] - xl_[i]));
    if (has_xu_[i]) phi -= mu_ * std::log(xu_[i] - x[i]) - (has_xl_[i] ? 0.0 : kKappaD * mu_ * (xu_[i] - x[i]));
  }
  for (int r = 0; r < m_; ++r) {
    if (has_gl_[r]) phi -= mu_ * std::log(s[r] - gl_[r]) - (has_gu_[r] ? 0.0 : kKappaD * mu_ * (s[r] - gl_[r]));
    if (has_gu_[r]) phi -= mu_ * std::log(gu_[r] - s[r]) - (has_gl_[r] ? 0.0 : kKappaD * mu_ * (gu_[r] - s[r]));
  }
  return phi;
}

void Ipm::barrierGradient(double mu, Vec& gx, Vec& gs) const {
  gx = grad_;
  for (int i = 0; i < n_; ++i) {
    if (fixed_[i]) gx[i] = 0.0;
    if (has_xl_[i]) gx[i] -= mu / (x_[i] - xl_[i]) - (has_xu_[i] ? 0.0 : kKappaD * mu);
    if (has_xu_[i]) gx[i] += mu / (xu_[i] - x_[i]) - (has_xl_[i] ? 0.0 : kKappaD * mu);
  }
  gs.setZero(m_);
  for (int r = 0; r < m_; ++r) {
    if (has_gl_[r]) gs[r] -= mu / (s_[r] - gl_[r]) - (has_gu_[r] ? 0.0 : kKappaD * mu);
    if (has_gu_[r]) gs[r] += mu / (gu_[r] - s_[r]) - (has_gl_[r] ? 0.0 : kKappaD * mu);
  }
}

// The stationarity, primal and complementarity residuals; the dual part in both the scaled and the NLP's
// variables (one pass serves the convergence test and the unscaled checks).
Ipm::OptimalityError Ipm::optimalityError(double mu) const {
  const SparsePattern& p = nlp_.pattern();
  Vec rd = grad_;
  for (std::size_t t = 0; t < p.jac_rows.size(); ++t) rd[p.jac_cols[t]] += jac_[t] * y_[p.jac_rows[t]];
  rd -= zl_;
  rd += zu_;
  OptimalityError e;
  double mult1 = y_.lpNorm<1>(), bmult1 = 0.0;
  int nb = 0;
  for (int i = 0; i < n_; ++i) {
    if (fixed_[i]) continue;
    e.dual = std::max(e.dual, std::abs(rd[i]));
    e.dual_unscaled = std::max(e.dual_unscaled, std::abs(rd[i] / D_[i]));
    if (has_xl_[i]) e.compl_err = std::max(e.compl_err, std::abs((x_[i] - xl_[i]) * zl_[i] - mu)), bmult1 += zl_[i], ++nb;
    if (has_xu_[i]) e.compl_err = std::max(e.compl_err, std::abs((xu_[i] - x_[i]) * zu_[i] - mu)), bmult1 += zu_[i], ++nb;
  }
  for (int r = 0; r < m_; ++r) {
    if (!ineq_[r]) continue;
    const double rs = std::abs(-y_[r] - vl_[r] + vu_[r]);
    e.dual = std::max(e.dual, rs);
    e.dual_unscaled = std::max(e.dual_unscaled, rs);
    if (has_gl_[r]) e.compl_err = std::max(e.compl_err, std::abs((s_[r] - gl_[r]) * vl_[r] - mu)), bmult1 += vl_[r], ++nb;
    if (has_gu_[r]) e.compl_err = std::max(e.compl_err, std::abs((gu_[r] - s_[r]) * vu_[r] - mu)), bmult1 += vu_[r], ++nb;
  }
  e.primal = m_ ? rp_.cwiseAbs().maxCoeff() : 0.0;
  e.sd = std::max(kSmax, (mult1 + bmult1) / std::max(1, m_ + nb)) / kSmax;
  e.sc = std::max(kSmax, bmult1 / std::max(1, nb)) / kSmax;
  return e;
}

void Ipm::safeguardMultipliers() {
  for (int i = 0; i < n_; ++i) {
    if (has_xl_[i]) {
      const double sl = x_[i] - xl_[i];
      zl_[i] = std::max(std::min(zl_[i], kKappaSigma * mu_ / sl), mu_ / (kKappaSigma * sl));
    }
    if (has_xu_[i]) {
      const double su = xu_[i] - x_[i];
      zu_[i] = std::max(std::min(zu_[i], kKappaSigma * mu_ / su), mu_ / (kKappaSigma * su));
    }
  }
  for (int r = 0; r < m_; ++r) {
    if (has_gl_[r]) {
      const double sl = s_[r] - gl_[r];
      vl_[r] = std::max(std::min(vl_[r], kKappaSigma * mu_ / sl), mu_ / (kKappaSigma * sl));
    }
    if (has_gu_[r]) {
      const double su = gu_[r] - s_[r];
      vu_[r] = std::max(std::min(vu_[r], kKappaSigma * mu_ / su), mu_ / (kKappaSigma * su));
    }
  }
}

// Least-squares equality multipliers: [I J'; J -E][w; y] = [-(grad f - z_l + z_u); E (v_l - v_u)], E = 1 on the
// inequality rows (their slack stationarity -y - v_l + v_u = 0 enters the least squares).
void Ipm::leastSquaresMultipliers() {
  Vec dxd = Vec::Ones(n_), dc(m_), rx = -(grad_ - zl_ + zu_), rc = Vec::Zero(m_);
  for (int r = 0; r < m_; ++r) {
    dc[r] = ineq_[r] ? 1.0 : 0.0;
    if (ineq_[r]) rc[r] = vl_[r] - vu_[r];
  }
  ++stats_.factorizations;
  const KktStatus st = kkt_.factor(zero_hess_.data(), jac_.data(), dxd, dc);
  y_.setZero(m_);
  if (st == KktStatus::kWrongInertia) return;
  Vec w, y;
  kkt_.solve(rx, rc, w, y);
  ++stats_.solves;
  if (m_ > 0 && y.allFinite() && y.cwiseAbs().maxCoeff() <= opt_.constr_mult_init_max) y_ = y;
}

// The bound multipliers of a primal-dual warm start (scaled as x), and those of the slacks from the sign of
// y (the slack rows of the dual residual, -y - v_l + v_u = 0, hold at the neighbour's solution).
void Ipm::warmMultipliers() {
  const double floor = warm_->mult_bound_push;
  for (int i = 0; i < n_; ++i) {
    if (has_xl_[i]) zl_[i] = std::max(warm_->z_l[i] * D_[i], floor);
    if (has_xu_[i]) zu_[i] = std::max(warm_->z_u[i] * D_[i], floor);
  }
  for (int r = 0; r < m_; ++r) {
    if (has_gl_[r]) vl_[r] = std::max(-warm_->y[r], floor);
    if (has_gu_[r]) vu_[r] = std::max(warm_->y[r], floor);
  }
}

void Ipm::initialize() {
  setupProblem();
  const bool warm = warm_ != nullptr && warm_->x.size() == n_;
  x_ = (warm ? warm_->x : nlp_.initialPoint()).cwiseQuotient(D_);
  for (int i = 0; i < n_; ++i)
    if (fixed_[i]) x_[i] = xl_[i];
  const double push = warm ? warm_->bound_push : opt_.bound_push, frac = warm ? warm_->bound_push : opt_.bound_frac;
  pushIntoBounds(x_, xl_, xu_, has_xl_, has_xu_, push, frac);
  g_.resize(m_);
  if (!evalFunctions(x_, f_, g_)) throw std::runtime_error("interior point: the initial point cannot be evaluated");
  s_ = g_;
  pushIntoBounds(s_, gl_, gu_, has_gl_, has_gu_, push, frac);
  const bool primal_dual = warm && warm_->hasMultipliers(n_, m_);
  mu_ = primal_dual ? warm_->mu_init_primal_dual : warm ? warm_->mu_init : opt_.mu_init;
  tau_ = std::max(kTauMin, 1.0 - mu_);
  zl_.setZero(n_);
  zu_.setZero(n_);
  vl_.setZero(m_);
  vu_.setZero(m_);
  const bool compl_mult = warm && warm_->complementary_multipliers;
  for (int i = 0; i < n_; ++i) {  // bound_mult_init, or (warm) complementarity mu
    if (has_xl_[i]) zl_[i] = compl_mult ? mu_ / (x_[i] - xl_[i]) : opt_.bound_mult_init;
    if (has_xu_[i]) zu_[i] = compl_mult ? mu_ / (xu_[i] - x_[i]) : opt_.bound_mult_init;
  }
  for (int r = 0; r < m_; ++r) {
    if (has_gl_[r]) vl_[r] = compl_mult ? mu_ / (s_[r] - gl_[r]) : opt_.bound_mult_init;
    if (has_gu_[r]) vu_[r] = compl_mult ? mu_ / (gu_[r] - s_[r]) : opt_.bound_mult_init;
  }
  if (primal_dual) warmMultipliers();
  y_.setZero(m_);
  grad_.resize(n_);
  if (warm && warm_->y.size() == m_) {
    y_ = warm_->y;  // given: the derivatives are evaluated once, with these multipliers
  } else {
    if (!evalDerivatives()) throw std::runtime_error("interior point: the initial derivatives cannot be evaluated");
    leastSquaresMultipliers();
  }
  if (!evalDerivatives()) throw std::runtime_error("interior point: the initial derivatives cannot be evaluated");
  primalResidual(g_, s_, rp_);
  const double th = theta(g_, s_);
  filter_.start(1e4 * std::max(1.0, th));
  theta_min_ = 1e-4 * std::max(1.0, th);
  adaptive_ = opt_.mu_strategy == "adaptive" && !primal_dual;
  free_mode_ = true;
  progress_filter_.reset(std::numeric_limits<double>::infinity());
  mu_max_ = 0.0;
}

void Ipm::printIteration(char mode, const OptimalityError& e) const {
  if (!opt_.progress) return;
  const double dual = e.dual_unscaled, primal = e.primal;
  std::fprintf(stderr, "  iter %4d%c cost %12.6e  infeas %9.2e  dual %9.2e  mu %8.1e  |dx| %8.1e  reg %8.1e  a %8.2e %c %d\n",
               stats_.iterations, mode, f_, primal, dual, mu_, d_.x.size() ? d_.x.cwiseAbs().maxCoeff() : 0.0,
               delta_w_, alpha_primal_, ls_type_, ls_trials_);
}

void Ipm::storeAcceptablePoint() {
  AcceptablePoint& a = acceptable_point_;
  a.valid = true;
  a.x = x_, a.s = s_, a.y = y_, a.zl = zl_, a.zu = zu_, a.vl = vl_, a.vu = vu_, a.g = g_;
  a.f = f_;
}

// As Ipopt's line search before its restoration phase: at an acceptable point the solve ends there; at an almost
// feasible one (theta <= 1e-2 tol) a restoration cannot reduce the infeasibility, and the last acceptable iterate
// is the result if there was one.
bool Ipm::afterFailedLineSearch(bool acceptable, IpmStatus& stop) {
  if (acceptable) {
    stop = IpmStatus::kAcceptable;
    return false;
  }
  if (theta(g_, s_) <= 1e-2 * opt_.tol) {
    stop = acceptable_point_.valid ? IpmStatus::kAcceptable : IpmStatus::kRestorationFailed;
    if (acceptable_point_.valid) {
      const AcceptablePoint& a = acceptable_point_;
      x_ = a.x, s_ = a.s, y_ = a.y, zl_ = a.zl, zu_ = a.zu, vl_ = a.vl, vu_ = a.vu, g_ = a.g;
      f_ = a.f;
    }
    return false;
  }
  if (restoration()) return true;
  stop = IpmStatus::kRestorationFailed;
  return false;
}

IpmResult Ipm::run() {
  t0_ = std::chrono::steady_clock::now();
  IpmResult res;
  try {
    initialize();
  } catch (const std::runtime_error&) {
    res.status = IpmStatus::kEvaluationError;
    return res;
  }
  res.status = IpmStatus::kMaxIterations;
  for (;;) {
    primalResidual(g_, s_, rp_);
    const OptimalityError e = optimalityError(0.0);
    const double dual = e.dual_unscaled, primal = e.primal, compl_err = e.compl_err;
    const double err = e.scaled();
    nlp_error_ = err;
    printIteration(' ', e);
    if (err <= opt_.tol && dual <= opt_.dual_inf_tol && primal <= opt_.constr_viol_tol && compl_err <= opt_.compl_inf_tol) {
      res.status = IpmStatus::kSolved;
      break;
    }
    const bool acceptable = err <= opt_.acceptable_tol && primal <= opt_.acceptable_constr_viol_tol &&
                            compl_err <= opt_.acceptable_compl_inf_tol;
    acceptable_count_ = acceptable ? acceptable_count_ + 1 : 0;
    if (acceptable) storeAcceptablePoint();
    if (acceptable_count_ >= opt_.acceptable_iter) {
      res.status = IpmStatus::kAcceptable;
      break;
    }
    if (stats_.iterations >= opt_.max_iter) {
      res.status = IpmStatus::kMaxIterations;
      break;
    }
    if (elapsed() > opt_.max_cpu_time) {
      res.status = IpmStatus::kMaxTime;
      break;
    }
    updateBarrier();
    if (!computeDirection()) {
      res.status = IpmStatus::kNumericalTrouble;
      break;
    }
    bool stepped = lineSearch();
    if (!stepped && adaptive_ && free_mode_) {
      // The free barrier parameter gave a step the filter cannot accept (typically mu far below the constraint
      // violation): retry once in the monotone mode before the restoration phase.
      enterMonotoneMode();
      if (!computeDirection()) {
        res.status = IpmStatus::kNumericalTrouble;
        break;
      }
      stepped = lineSearch();
    }
    if (!stepped && !afterFailedLineSearch(acceptable, res.status)) break;
    ++stats_.iterations;
    if (!evalDerivatives()) {
      res.status = IpmStatus::kEvaluationError;
      break;
    }
  }
  for (int i = 0; i < n_; ++i) {
    if (has_xl_[i]) x_[i] = std::max(x_[i], xl_orig_[i]);
    if (has_xu_[i]) x_[i] = std::min(x_[i], xu_orig_[i]);
  }
  res.x = unscaled(x_);
  res.y = y_;
  res.z_l = zl_.cwiseQuotient(D_);
  res.z_u = zu_.cwiseQuotient(D_);
  res.objective = f_;
  double viol = 0.0;
  for (int r = 0; r < m_; ++r) viol = std::max({viol, gl_orig_[r] - g_[r], g_[r] - gu_orig_[r]});
  res.constraint_violation = viol;
  stats_.time_total = elapsed();
  res.stats = stats_;
  return res;
}

}  // namespace detail
}  // namespace centaur::ocp_solver
