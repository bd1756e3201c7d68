#pragma once
// Dense convex quadratic program, solved by the Goldfarb-Idnani dual active-set method:
//
//   minimise    1/2 x'Hx + g'x                 x in R^n, H symmetric positive semidefinite
//   subject to  A_eq x  = b_eq                 (m_eq rows)
//               c_lo <= C x <= c_up             (m_in two-sided rows, any bound may be -inf/+inf)
//               x_lo <= x   <= x_up             (box bounds, optional, any bound may be -inf/+inf)
//
// Why our own: Debian ships no dense QP solver fast enough for a 1 kHz whole-body stack (ALGLIB's took 2-9 ms
// on a 40-variable problem). This one is small, documented in docs/qp.md and tested against Ipopt.
//
// Multiplier convention (KKT stationarity):   H x + g = A_eq' y_eq + C' y_in + y_box
//   y_in[i] >= 0 when the LOWER bound of row i is active, <= 0 when the UPPER bound is active, 0 if inactive;
//   same for y_box; y_eq has any sign.
//
// "Optimal" is only reported for a point that passes a KKT check against tolerances scaled to the data (every row
// and bound feasible, active ones at their bound, multipliers correctly signed, stationarity). The dual method
// needs H positive definite: when H is numerically singular (a Cholesky pivot below singular_tol * max_i H_ii,
// or a failed factorisation of a positive semidefinite H), or when the direct answer fails the KKT check, the
// problem is solved by proximal-point iterations, x_{k+1} = argmin f(x) + rho/2 ||x - x_k||^2 over the same
// constraints (strictly convex, warm-started), which converge to an optimum of the semidefinite problem or reveal
// that it is unbounded (kUnbounded, with a ray).
//
// Lifecycle (Model/Data split): resize(n, m_eq_max, m_in_max) allocates everything; solve() never allocates,
// never throws, and returns a status that must be checked. A row with c_lo == c_up (or x_lo == x_up) is
// treated as an equality. Warm start: the previous optimal active set is re-imposed first, then the dual
// method continues from there (the answer does not depend on it; only the work does).
#include <Eigen/Core>

#include <vector>

namespace centaur {

enum class QpStatus {
  kOptimal = 0,          ///< a point that passed the KKT check (unique if H > 0)
  kInfeasible,           ///< the constraints admit no point (or c_lo > c_up / x_lo > x_up)
  kIterationLimit,       ///< max_iterations active-set changes, or max_proximal_iterations, without convergence
  kInvalidInput,         ///< NaN/Inf in H, g, matrices or equality rhs; NaN bound; sizes beyond resize()
  kNotPositiveDefinite,  ///< H is not convex: an eigenvalue below -proximal_rho * max_i H_ii (or a diagonal < 0)
  kUnbounded,            ///< feasible, but 1/2 x'Hx + g'x decreases without bound along ray() (H singular)
  kInaccurate,           ///< no point passed the KKT check (H too ill-conditioned for the tolerances)
};

/// Callers that build H = sum_t w_t A_t'A_t + eps I (regularised least squares: the whole-body stack, the force
/// distribution) keep eps >= kMinRegularisationRatio * max_t w_t. Then the relative regularisation
/// eps / max_i H_ii stays above the solver's singular_tol (1e-10) for rows with |A_row|^2 up to 1e3, where the
/// direct dual method is fast and accurate (measured, docs/qp.md); below it H counts as singular and the much
/// slower proximal-point iterations run.
constexpr double kMinRegularisationRatio = 1e-7;

/// "optimal", "infeasible", ... for messages.
const char* toString(QpStatus status);

struct QpSettings {
  /// Max active-set changes per solve (per proximal iteration); 0 = automatic, 10 * (n + m_eq + m_in) + 50.
  int max_iterations = 0;
  /// A constraint counts as violated when (bound - row.x) / ||row|| > feasibility_tol * max(1, |bound|/||row||).
  /// (distance to the constraint's hyperplane, relative for large bounds)
  double feasibility_tol = 1e-11;
  /// A new constraint normal is linearly dependent on the active ones when the component of J'n outside the
  /// active subspace is below dependency_tol * ||J'n|| (J = L^-T Q, the H-metric). Dependent equalities that are
  /// consistent (residual within feasibility_tol) are skipped; inconsistent ones make the problem infeasible.
  double dependency_tol = 1e-10;
  /// When a violated constraint is linearly dependent on the active ones and no active multiplier can be
  /// released, the problem is infeasible, unless the violation is below infeasibility_tol (same scaling as
  /// feasibility_tol): then it is a rounding artefact of a degenerate problem and the constraint is ignored.
  double infeasibility_tol = 1e-9;
  /// KKT check before "optimal": every row and bound violated by at most kkt_tol (scaled as feasibility_tol),
  /// active ones within kkt_tol of their bound, multipliers of the wrong sign and the stationarity residual
  /// ||H x + g - A_eq'y_eq - C'y_in - y_box||_inf at most kkt_tol * max(||H x||_inf, ||g||_inf, max_k |y_k| ||n_k||).
  double kkt_tol = 1e-9;
  /// H is numerically singular (solved by proximal-point iterations) when a pivot of its Cholesky factorisation,
  /// L_jj^2, is below singular_tol * max_i H_ii; directions of curvature below it count as flat (unboundedness).
  double singular_tol = 1e-10;
  /// rho of the proximal-point iterations, relative to max_i H_ii (1 if H = 0): each iteration is a strictly convex
  /// QP with H + rho I, of condition number ~ 1 / proximal_rho at worst.
  double proximal_rho = 1e-7;
  /// Proximal-point iterations per solve (each a warm-started QP); then kIterationLimit.
  int max_proximal_iterations = 100;
  /// Re-impose the previous optimal active set at the start of solve().
  bool warm_start = true;
};

class QpSolver {
 public:
  QpSolver() = default;
  QpSolver(int n, int m_eq_max, int m_in_max) { resize(n, m_eq_max, m_in_max); }

  /// Allocate for at most n variables, m_eq_max equality and m_in_max inequality rows. Forgets the warm start.
  void resize(int n, int m_eq_max, int m_in_max);
  QpSettings& settings() { return settings_; }
  const QpSettings& settings() const { return settings_; }
  /// Forget the previous active set (and solution): the next solve is cold.
  void resetWarmStart() {
    n_prev_ = 0;
    prev_n_ = -1;
  }

  /// Solve. Sizes: H n x n (n <= the n of resize(); symmetric, its lower triangle is factorised), g n, A_eq m_eq x n (m_eq <= m_eq_max), b_eq m_eq,
  /// C m_in x n, c_lo/c_up m_in, x_lo/x_up n or size 0 (no box bounds). Never allocates, never throws.
  [[nodiscard]] QpStatus solve(const Eigen::Ref<const Eigen::MatrixXd>& H, const Eigen::Ref<const Eigen::VectorXd>& g,
                               const Eigen::Ref<const Eigen::MatrixXd>& A_eq,
                               const Eigen::Ref<const Eigen::VectorXd>& b_eq,
                               const Eigen::Ref<const Eigen::MatrixXd>& C,
                               const Eigen::Ref<const Eigen::VectorXd>& c_lo,
                               const Eigen::Ref<const Eigen::VectorXd>& c_up,
                               const Eigen::Ref<const Eigen::VectorXd>& x_lo,
                               const Eigen::Ref<const Eigen::VectorXd>& x_up);

  // ---- results of the last solve (valid when it returned kOptimal) ----
  QpStatus status() const { return status_; }
  Eigen::VectorBlock<const Eigen::VectorXd> x() const { return x_.head(n_); }  ///< n (kUnbounded: a feasible point)
  auto yEq() const { return y_eq_.head(m_eq_); }   ///< m_eq
  auto yIneq() const { return y_in_.head(m_in_); } ///< m_in
  Eigen::VectorBlock<const Eigen::VectorXd> yBox() const { return y_box_.head(n_); }  ///< n (0 without box)
  double objective() const { return objective_; }  ///< 1/2 x'Hx + g'x
  /// kUnbounded: unit direction d with H d ~ 0, g'd < 0, along which x() + t d stays feasible for all t >= 0.
  Eigen::VectorBlock<const Eigen::VectorXd> ray() const { return ray_.head(n_); }
  int iterations() const { return iterations_; }   ///< active-set changes in the last solve
  /// Proximal-point iterations of the last solve (0 when H was positive definite and the direct answer passed).
  int proximalIterations() const { return prox_iterations_; }
  int numActive() const { return iq_; }            ///< size of the final active set (incl. equalities)
  int numVariables() const { return n_; }  ///< n of the last solve
  int capacity() const { return n_max_; }

 private:
  // A constraint in the form n'x >= b (inequality) or n'x = b (equality). Ids: [0, m_eq) equality rows,
  // m_eq + 2i (+1) lower (upper) side of C row i, m_eq + 2 m_in + 2j (+1) lower (upper) bound of x_j.
  double normalDot(int id, const Eigen::VectorXd& v) const;
  double rhs(int id) const;
  double normalNorm(int id) const;   // ||n|| (1 for equality rows: unused there)
  void addNormal(int id, double scale, Eigen::VectorXd& v) const;  // v += scale * n_id
  void computeD(int id);             // d_ = J' n_id
  void computeStep();                // z_ = J2 d2, r_ = R^-1 d1 (uses d_)
  void addToActiveSet(int id, bool equality);  // QR update with d_ (d_ is destroyed)
  void dropFromActiveSet(int pos);             // QR downdate
  // On the active set: x_out = J1 R^-T b_A - J2 J2' gv, u_out = R^-1 (R^-T b_A + J1' gv), b_A in tmp_ (destroyed).
  void activeSetSolve(const Eigen::Ref<const Eigen::VectorXd>& gv, Eigen::VectorXd& x_out, Eigen::VectorXd& u_out);
  void recomputePrimalDual();        // x and u from the current factorisation (warm start)
  void restoreDualFeasibility();     // recompute, dropping negative inequality multipliers
  int mostNegativeMultiplier() const;  // active-set position of the most negative inequality multiplier, -1: none
  bool isDependent() const;          // from d_ after computeD
  void applyH(const Eigen::VectorXd& v, Eigen::VectorXd& out) const;  // out = (H + shift_ I) v
  // L_ = chol(H + shift I); false if the factorisation fails. Sets shift_.
  bool factorize(double shift);
  void solveWithFactor(Eigen::VectorXd& v) const;  // v <- (H + shift_ I)^-1 v
  // x = -H^-1 g if no equality, no warm-start set and no row or bound violated (then the optimum)
  bool unconstrainedMinimiserIsFeasible(int n_box, bool warm);
  // The dual method on the factor in L_ for H + shift_ I and *g_: equalities, warm start, main loop, KKT check.
  QpStatus solveDual(bool warm);
  QpStatus dualLoop();               // adds the most violated constraint until none is (main loop)
  int mostViolated();                // that constraint side (id), -1 if none is violated; sets cx_ = C x
  bool kktHolds();                   // KKT check of x_, u_ for H + shift_ I and *g_ (sets hx_); needs cx_ = C x
  void refine();                     // x, u recomputed on the active set + one refinement step, dual feasible
  void rememberActiveSet();          // prev_active_ <- the inequalities of the active set (warm start)
  QpStatus fail(QpStatus status);    // no warm start from a failed solve
  QpStatus solveProximal(const Eigen::Ref<const Eigen::VectorXd>& g);  // H singular or ill-conditioned
  bool polishHolds();                // proximal iterate polished on its active set; KKT check of the original
  // d (n) a flat descent direction (sets ray_ = d / ||d||)? inf: a ray of unbounded descent; t > 0: blocked by a
  // bound at distance t along ray_; 0: not a flat descent (or blocked at once)
  double flatDescent(const Eigen::VectorXd& d);

  QpSettings settings_;
  int n_max_ = 0, n_ = 0, m_eq_max_ = 0, m_in_max_ = 0;
  int m_eq_ = 0, m_in_ = 0;
  bool has_box_ = false;

  // Problem views of the current solve (raw pointers into the caller's Refs, valid only during solve()).
  const Eigen::Ref<const Eigen::MatrixXd>* A_eq_ = nullptr;
  const Eigen::Ref<const Eigen::VectorXd>* b_eq_ = nullptr;
  const Eigen::Ref<const Eigen::MatrixXd>* C_ = nullptr;
  const Eigen::Ref<const Eigen::VectorXd>* c_lo_ = nullptr;
  const Eigen::Ref<const Eigen::VectorXd>* c_up_ = nullptr;
  const Eigen::Ref<const Eigen::VectorXd>* x_lo_ = nullptr;
  const Eigen::Ref<const Eigen::VectorXd>* x_up_ = nullptr;
  const Eigen::Ref<const Eigen::VectorXd>* g_ = nullptr;   // g, or g - rho x_k in a proximal iteration
  const Eigen::Ref<const Eigen::MatrixXd>* H_ = nullptr;
  double shift_ = 0.0;    // the dual method works on H + shift_ I (rho in a proximal iteration)
  double h_scale_ = 0.0;  // max_i H_ii

  Eigen::MatrixXd L_;   // n x n, Cholesky factor (in place, lower triangle)
  Eigen::MatrixXd J_;   // n x n, J = L^-T Q
  Eigen::MatrixXd R_;   // n x n, upper triangular iq x iq block in use
  Eigen::VectorXd d_, z_, r_, u_, x_, tmp_;
  Eigen::VectorXd hx_, res_, w_;     // (H + shift) x, KKT residual, refinement step
  Eigen::VectorXd xk_, gk_, ray_;    // proximal centre x_k, g - rho x_k, unbounded ray
  Eigen::VectorXd xb_, ub_;          // the proximal iterate before polishing
  Eigen::VectorXd row_norm_;  // ||C_i||, m_in_max
  Eigen::VectorXd cx_;        // C x, m_in_max
  Eigen::VectorXd y_eq_, y_in_, y_box_;
  std::vector<int> active_;       // active ids by position (size n)
  std::vector<char> is_eq_;       // per position: equality (not droppable)
  std::vector<char> in_active_;   // per id
  std::vector<int> prev_active_;  // previous optimal inequality ids (warm start)
  int n_prev_ = 0;
  int prev_n_ = -1, prev_m_eq_ = -1, prev_m_in_ = -1;
  bool prev_box_ = false;
  int iq_ = 0;
  int n_eq_active_ = 0;           // equalities at the front of the active set
  int iterations_ = 0;
  int max_it_ = 0;
  int prox_iterations_ = 0;
  double objective_ = 0.0;
  QpStatus status_ = QpStatus::kInvalidInput;
};

}  // namespace centaur
