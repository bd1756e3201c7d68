#pragma once
// Internal to the interior-point method (interior_point.cpp, ipm_direction.cpp, ipm_line_search.cpp): the
// problem in scaled variables, the primal-dual iterate and the search direction.
#include <algorithm>
#include <chrono>

#include "ocp_solver/interior_point.hpp"

namespace centaur::ocp_solver::detail {

using Vec = Eigen::VectorXd;

struct Direction {
  Vec x, s, y, zl, zu, vl, vu;
};

/// The right-hand side of the reduced system for one barrier parameter, and the slack part it eliminated.
struct StepRhs {
  double mu = 0.0;
  Vec rx, rc, rho_s;
};

class Ipm {
 public:
  Ipm(Nlp& nlp, KktSolver& kkt, const IpmOptions& opt, const WarmStart* warm);
  IpmResult run();

 private:
  // problem
  void setupProblem();
  bool evalFunctions(const Vec& x, double& f, Vec& g);
  bool evalDerivatives();
  Vec unscaled(const Vec& x) const { return x.cwiseProduct(D_); }
  // iterate
  void initialize();
  void warmMultipliers();  // bound and slack multipliers of a primal-dual warm start
  void pushIntoBounds(Vec& v, const Vec& lo, const Vec& hi, const std::vector<char>& has_lo,
                      const std::vector<char>& has_hi, double push, double frac) const;
  void leastSquaresMultipliers();
  void primalResidual(const Vec& g, const Vec& s, Vec& rp) const;
  double theta(const Vec& g, const Vec& s) const;
  double barrierObjective(double f, const Vec& x, const Vec& s) const;
  void barrierGradient(double mu, Vec& gx, Vec& gs) const;
  /// Ipopt's optimality error of the barrier problem (mu > 0) or of the NLP (mu = 0), its parts computed once for
  /// both of its uses: scaled() for the convergence test, the parts for the checks in the NLP's own variables.
  struct OptimalityError {
    double dual = 0.0;           // largest stationarity residual (scaled variables)
    double dual_unscaled = 0.0;  // the same in the NLP's variables
    double primal = 0.0, compl_err = 0.0;
    double sd = 1.0, sc = 1.0;  // Ipopt's s_d and s_c
    double scaled() const { return std::max({dual / sd, primal, compl_err / sc}); }
  };
  OptimalityError optimalityError(double mu) const;
  void safeguardMultipliers();
  // barrier parameter (ipm_barrier.cpp)
  void updateBarrier();
  void monotoneUpdate();
  void enterMonotoneMode();  // adaptive: leave the free mode, mu from the average complementarity
  bool adaptiveDirection();
  double averageComplementarity() const;
  struct QualityBase {
    double dual = 0.0, primal = 0.0;
    int nd = 0;
  };
  QualityBase qualityBase() const;
  /// The bounded components of the affine and the centring step, one entry per bound in the order of the
  /// variables then the slacks (lower before upper): what the quality function reads for every sigma.
  struct QualityTerms {
    // gap: distance to the bound; (b0 + alpha dv) - b1: that distance after a primal step alpha, where dv =
    // sav + sigma sdv is the step of the component signed towards its bound's interior (lower: b0 = v, b1 = lo,
    // sign +1; upper: b0 = hi - v, b1 = 0, sign -1); z + alpha_dual (az + sigma dzd): the bound's multiplier.
    std::vector<double> gap, b0, b1, sav, sdv, z, az, dzd;
  };
  void qualityTerms(const Direction& aff, const Direction& cen, QualityTerms& t) const;
  double qualityFunction(const QualityTerms& t, double sigma, double tau, const QualityBase& base) const;
  void combine(const Direction& aff, const Direction& cen, double sigma, Direction& d) const;
  bool progressAcceptable() const;
  void rememberProgress();
  // direction (ipm_direction.cpp)
  bool computeDirection();
  bool factorWithCorrection();
  void assembleRhs(const Vec& rp, double mu, StepRhs& rhs) const;
  void recover(const StepRhs& rhs, Direction& d) const;  // the slack and bound-multiplier steps
  void solveAndRecover(const Vec& rp, Direction& d);
  /// The affine-scaling (mu = 0) and the centring (mu = mu_cen) steps with the same factorization, solved together.
  void solveAffineAndCentring(double mu_cen);
  // line search (ipm_line_search.cpp)
  bool lineSearch();
  double maxStep(const Vec& v, const Vec& dv, const Vec& lo, const Vec& hi, const std::vector<char>& has_lo,
                 const std::vector<char>& has_hi, double tau) const;
  double maxDualStep(const Direction& d, double tau) const;
  /// 0: rejected, 1: accepted by the Armijo condition (f-type), 2: by sufficient decrease of theta or phi (h-type).
  int acceptance(double theta_t, double phi_t, double alpha, double gpd, double theta0, double phi0);
  bool trialPoint(const Direction& d, double alpha);  // x_trial_, s_trial_, f_trial_, g_trial_
  bool secondOrderCorrection(double alpha, double gpd, double theta0, double phi0, double theta_t);
  /// Backtracking from alpha on d_ against the references of the current point; false below the minimum step.
  bool backtrack(double alpha, double a_dual, double gpd, double theta0, double phi0, bool allow_soc);
  /// Ipopt's watchdog: after kWatchdogTrigger consecutive shortened steps, full steps for up to kWatchdogTrials
  /// iterations measured against the point where it started; if none is acceptable there, back to that point.
  bool watchdogStep(double a_max, double a_dual);
  void stopWatchdog();
  void acceptStep(const Direction& d, double alpha_primal, double alpha_dual);
  bool restoration();
  void printIteration(char mode, const OptimalityError& e) const;
  double elapsed() const;

  Nlp& nlp_;
  KktSolver& kkt_;
  IpmOptions opt_;
  const WarmStart* warm_;
  int n_ = 0, m_ = 0;
  Vec D_;  // variable scale
  Vec xl_, xu_, gl_, gu_;  // bounds as the method sees them (scaled x, relaxed)
  Vec xl_orig_, xu_orig_, gl_orig_, gu_orig_;  // the bounds before the relaxation
  std::vector<char> fixed_, has_xl_, has_xu_, ineq_, has_gl_, has_gu_;
  std::vector<int> x_bounded_, s_bounded_;  // variables and rows with a bound, ascending
  QualityTerms quality_terms_;  // workspace of adaptiveDirection()
  std::vector<double> jac_scale_, hess_scale_;

  // iterate (scaled)
  Vec x_, s_, y_, zl_, zu_, vl_, vu_;
  double f_ = 0.0;
  Vec g_, grad_, rp_;
  std::vector<double> jac_, hess_, zero_hess_;
  double mu_ = 0.1, tau_ = 0.99;
  double nlp_error_ = 0.0;  // the scaled NLP error of the current iterate (computed once per iteration by run())
  bool tiny_step_ = false;

  // direction and linear algebra
  Direction d_;
  Vec dxdiag_, dc_, sigma_s_;
  StepRhs rhs_, rhs_cen_;
  Vec extra_diag_;                   // restoration: its proximal term
  const double* hess_in_use_ = nullptr;
  double delta_w_ = 0.0, delta_w_last_ = 0.0, delta_c_ = 0.0;
  bool hess_degenerate_ = false;
  int degen_iters_ = 0;

  // line search
  Filter filter_;
  double theta_min_ = 0.0;
  double alpha_primal_ = 0.0, alpha_dual_ = 0.0;
  char ls_type_ = ' ';
  int ls_trials_ = 0;
  Vec x_trial_, s_trial_, g_trial_;
  double f_trial_ = 0.0;
  struct Watchdog {
    bool active = false;
    int shortened = 0;  // consecutive accepted steps shorter than their first trial
    int trials = 0;     // full steps taken since the watchdog started
    double mu = -1.0;   // the barrier parameter it counts for (a new one resets it)
    Vec x, s, y, zl, zu, vl, vu, g, rp;  // the point where it started, its direction and line-search references
    double f = 0.0, theta = 0.0, phi = 0.0, gpd = 0.0, alpha_test = 1.0;
    Direction d;
  } wd_;

  int acceptable_count_ = 0;
  // Ipopt's backup point: the last iterate that met the acceptable tolerances, taken back when a line search fails
  // at an almost feasible point (no restoration can help there).
  struct AcceptablePoint {
    bool valid = false;
    Vec x, s, y, zl, zu, vl, vu, g;
    double f = 0.0;
  } acceptable_point_;
  void storeAcceptablePoint();
  /// After a line search that failed: true if the restoration phase found a point to go on from; false with the
  /// status to stop with (kAcceptable where Ipopt stops at an acceptable point, else kRestorationFailed).
  bool afterFailedLineSearch(bool acceptable, IpmStatus& stop);
  // adaptive barrier: free mode (mu chosen each iteration by the quality function), fixed mode (monotone)
  bool adaptive_ = false, free_mode_ = true;
  Filter progress_filter_;  // (constraint violation, objective) of the accepted free-mode iterates
  double mu_max_ = 0.0;
  Direction aff_, cen_;
  IpmStats stats_;
  std::chrono::steady_clock::time_point t0_;
};

}  // namespace centaur::ocp_solver::detail
