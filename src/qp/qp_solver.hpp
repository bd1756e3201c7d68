#pragma once
// Dense strictly convex quadratic program, solved by the Goldfarb-Idnani dual active-set method:
//
//   minimise    1/2 x'Hx + g'x                 x in R^n, H symmetric positive definite
//   subject to  A_eq x  = b_eq                 (m_eq rows)
//               c_lo <= C x <= c_up             (m_in two-sided rows, any bound may be -inf/+inf)
//               x_lo <= x   <= x_up             (box bounds, optional, any bound may be -inf/+inf)
//
// Why our own: Debian ships no dense QP solver fast enough for a 1 kHz whole-body stack (ALGLIB's took 2-9 ms
// on a 40-variable problem). This one is small (one file), documented in docs/qp.md and tested against Ipopt.
//
// Multiplier convention (KKT stationarity):   H x + g = A_eq' y_eq + C' y_in + y_box
//   y_in[i] >= 0 when the LOWER bound of row i is active, <= 0 when the UPPER bound is active, 0 if inactive;
//   same for y_box; y_eq has any sign.
//
// Lifecycle (Model/Data split): resize(n, m_eq_max, m_in_max) allocates everything; solve() never allocates,
// never throws, and returns a status that must be checked. A row with c_lo == c_up (or x_lo == x_up) is
// treated as an equality. Warm start: the previous optimal active set is re-imposed first, then the dual
// method continues from there (the answer does not depend on it; only the work does).
#include <Eigen/Cholesky>
#include <Eigen/Core>

#include <vector>

namespace centaur {

enum class QpStatus {
  kOptimal = 0,          ///< KKT point found (unique since H > 0)
  kInfeasible,           ///< the constraints admit no point (or c_lo > c_up / x_lo > x_up)
  kIterationLimit,       ///< max_iterations active-set changes without convergence
  kInvalidInput,         ///< NaN/Inf in H, g, matrices or equality rhs; NaN bound; sizes beyond resize()
  kNotPositiveDefinite,  ///< Cholesky of H failed (add regularisation)
};

/// "optimal", "infeasible", ... for messages.
const char* toString(QpStatus status);

struct QpSettings {
  /// Max active-set changes per solve; 0 = automatic, 10 * (n + m_eq + m_in) + 50.
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
  /// Forget the previous active set: the next solve is cold.
  void resetWarmStart() { n_prev_ = 0; }

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
  Eigen::VectorBlock<const Eigen::VectorXd> x() const { return x_.head(n_); }  ///< n
  auto yEq() const { return y_eq_.head(m_eq_); }   ///< m_eq
  auto yIneq() const { return y_in_.head(m_in_); } ///< m_in
  Eigen::VectorBlock<const Eigen::VectorXd> yBox() const { return y_box_.head(n_); }  ///< n (0 without box)
  double objective() const { return objective_; }  ///< 1/2 x'Hx + g'x
  int iterations() const { return iterations_; }   ///< active-set changes in the last solve
  int numActive() const { return iq_; }            ///< size of the final active set (incl. equalities)
  int numVariables() const { return n_; }  ///< n of the last solve
  int capacity() const { return n_max_; }

 private:
  // A constraint in the form n'x >= b (inequality) or n'x = b (equality). Ids: [0, m_eq) equality rows,
  // m_eq + 2i (+1) lower (upper) side of C row i, m_eq + 2 m_in + 2j (+1) lower (upper) bound of x_j.
  double normalDot(int id, const Eigen::VectorXd& v) const;
  double rhs(int id) const;
  double normalNorm(int id) const;
  void computeD(int id);             // d_ = J' n_id
  void computeStep();                // z_ = J2 d2, r_ = R^-1 d1 (uses d_)
  void addToActiveSet(int id, bool equality);  // QR update with d_ (d_ is destroyed)
  void dropFromActiveSet(int pos);             // QR downdate
  void recomputePrimalDual();        // x and u from the current factorisation (warm start)
  void restoreDualFeasibility();     // recompute, dropping negative inequality multipliers
  bool isDependent() const;          // from d_ after computeD
  // x = -H^-1 g if no equality, no warm-start set and no row or bound violated (then the optimum)
  bool unconstrainedMinimiserIsFeasible(const Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>>& llt, int n_box);

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
  const Eigen::Ref<const Eigen::VectorXd>* g_ = nullptr;
  const Eigen::Ref<const Eigen::MatrixXd>* H_ = nullptr;

  Eigen::MatrixXd L_;   // n x n, Cholesky factor (in place)
  Eigen::MatrixXd J_;   // n x n, J = L^-T Q
  Eigen::MatrixXd R_;   // n x n, upper triangular iq x iq block in use
  Eigen::VectorXd d_, z_, r_, u_, x_, tmp_;
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
  int iterations_ = 0;
  double objective_ = 0.0;
  QpStatus status_ = QpStatus::kInvalidInput;
};

}  // namespace centaur
