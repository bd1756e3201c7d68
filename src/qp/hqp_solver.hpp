#pragma once
// Hierarchical QP: solves a Stack (qp/stack.hpp) as a cascade of dense QPs, one per priority level.
//
// Level k (0 = highest) minimises
//     sum_{terms t in level k} scale_t || A_t x - lambda_t b_t ||^2_{W_t}  +  eps ||x||^2
//     s.t.  A_j x = A_j x_j*   for every level j < k     (each higher level keeps its optimal residual)
//           every constraint of the stack (box bounds and inequality rows)
// where A_j stacks the (selected) rows of level j's tasks and x_j* is level j's solution. Hence a lower level
// can never worsen a higher one (up to eps and the solver tolerances). eps = Stack::regularisation > 0 keeps
// every level's Hessian positive definite. Each level has its own QpSolver (warm-started from the previous
// tick's active set). The solution of the last level is returned.
//
// The equalities of level k are eliminated (null-space method): Z_k, an orthonormal basis of the null space of
// the stacked rows of the levels above, is built incrementally, Z_k = Z_{k-1} N with N a basis of
// null(A_{k-1} Z_{k-1}) from a rank-revealing (column-pivoted Householder) QR, and x = x_{k-1}* + Z_k y. Level k is then a QP in y (n - rank variables) with only inequality rows
// (the constraint rows times Z and the box bounds as rows Z), which is much smaller than the full problem
// and makes redundant rows of the levels above harmless (they do not increase the rank).
//
// Variables that no row touches stay out of the QPs. Level 0 leaves out the columns that none of its rows and no
// constraint row touches (e.g. the arms and the wheels' spin when the first level holds the feet): their only
// cost is eps x_j^2, so x_j = 0 (clipped to the box). They stay "free" (a unit column of Z, no QP variable)
// through the levels below until a level's rows first touch them; that level adds them to its QP as plain
// variables bounded by their box, and from then on they join the "dense" part of Z. So Z is kept as Zd (its
// rows on the dense variables) plus unit columns, and every product, null space and QP row is formed on the
// dense variables only. A touched variable that nothing couples (no off-diagonal Hessian entry, no row: e.g. a
// joint only a posture row touches) is solved in closed form and left out of the QP. Exact, and for CENTAURO's
// angular-momentum stack (feet / pelvis / momentum + posture) the pelvis level is an 8-variable QP instead of a
// 33-variable one, the last level an 18-variable QP instead of a 30-variable one.
//
// Lifecycle: configure(stack, n) checks the stack and allocates everything; then every tick
//   update()  -> each distinct task / constraint recomputes its A, b / bounds (once, even if shared)
//   solve(x)  -> no allocation, no throw, returns a status the caller must check.
#include <Eigen/Core>

#include <vector>

#include "qp/null_space.hpp"
#include "qp/qp_solver.hpp"
#include "qp/stack.hpp"

namespace centaur {

class HqpSolver {
 public:
  HqpSolver() = default;
  HqpSolver(const Stack& stack, int n) { configure(stack, n); }

  /// Check (every task and constraint has n columns, >= 1 level, regularisation > 0; throws
  /// std::invalid_argument naming the task) and allocate. Applies `settings` to every level's QpSolver.
  void configure(const Stack& stack, int n, const QpSettings& settings = QpSettings());

  /// update() on every distinct task and constraint of the stack. Must not allocate nor throw (the tasks'
  /// update() must honour that).
  void update();

  /// Box bounds of all constraints are intersected; crossed bounds (lo > up, e.g. a joint beyond its position
  /// limit by more than one tick at its velocity limit) are both set to the one of smaller magnitude.
  /// Solve the cascade with the tasks' current data; x (size n) receives the last level's solution, clipped to
  /// the box bounds (a change within the QP's feasibility tolerance) so that bounds hold exactly.
  /// On failure of level k, failedLevel() == k and x holds the solution of level k-1 (unchanged if k == 0).
  [[nodiscard]] QpStatus solve(Eigen::Ref<Eigen::VectorXd> x);

  int numVariables() const { return n_; }
  int numLevels() const { return static_cast<int>(stack_.levels.size()); }
  int failedLevel() const { return failed_level_; }
  const Stack& stack() const { return stack_; }
  QpSolver& levelSolver(int k) { return solvers_[k]; }
  /// Rank of the rows of the levels above level k in the last solve (0 for level 0).
  int levelRank(int k) const { return level_rank_[k]; }
  /// Solution of level k in the last solve (levels up to the failed one).
  const Eigen::VectorXd& levelSolution(int k) const { return level_x_[k]; }

  /// sum_t scale_t ||A_t x - lambda_t b_t||^2_W over level k's terms (no allocation).
  double levelCost(int k, const Eigen::Ref<const Eigen::VectorXd>& x);

 private:
  int checkStack(const Stack& stack, int n);  // configure: validate, collect tasks and constraints; max term rows
  void sizeWorkspaces(int max_term_rows, const QpSettings& settings);  // configure: every buffer of solve()
  void assembleFirst();           // level 0: its rows in E_, the used columns, H and g on them
  QpStatus solveFirst();          // level 0 on the columns its rows or the constraints touch (after assembleFirst)
  QpStatus solveReduced(int k);   // level k >= 1 in the null space of the levels above
  void levelRows(int k);          // level k's rows and targets into E_, bE_; the free variables they touch
  void reducedCost(int k);        // Hy, gy of level k's reduced QP
  int reducedRows(const Eigen::VectorXd& xp);  // its constraint and box rows (Cy_, ylo_, yup_) and bounds
  QpStatus solveReducedQp(int k, int rows);   // separable variables in closed form, the QP for the others

  void updateNullSpace(int k);    // Z_k from Z_{k-1} and the rows of level k-1
  void firstNullSpace(const Eigen::Ref<const Eigen::MatrixXd>& B);  // Zd of level 0's rows B, block by block
  void copyLevelRows(int k);      // E_, bE_ <- the rows and lambda b of level k's terms
  // M's columns of the dense variables, in their order: M itself if every variable is dense in order, else
  // gathered into work
  Eigen::Ref<const Eigen::MatrixXd> denseColumns(const Eigen::Ref<const Eigen::MatrixXd>& M,
                                                 Eigen::MatrixXd& work) const;
  void weigh(const Term& t, const Eigen::Ref<const Eigen::MatrixXd>& M, Eigen::Ref<Eigen::MatrixXd> WM);
  // level k >= 1: a diagonally weighted term's share of Hy, gy (its rows A, their dense-variable columns Ad,
  // residuals A x_{k-1}* - lambda b), exploiting the sparsity of its touched-free columns
  void addDiagonalTerm(const Term& t, const Eigen::Ref<const Eigen::MatrixXd>& A,
                       const Eigen::Ref<const Eigen::MatrixXd>& Ad, const Eigen::Ref<const Eigen::VectorXd>& res,
                       int nzd, int nt);

  Stack stack_;
  int n_ = 0;
  int m_in_ = 0;
  bool has_box_ = false;
  std::vector<Task*> tasks_;              // distinct tasks, in order of first appearance
  std::vector<Constraint*> constraints_;  // distinct constraints
  std::vector<int> level_offset_;         // first row of level k in E_ (size levels + 1)
  std::vector<QpSolver> solvers_;
  std::vector<Eigen::VectorXd> level_x_;
  Eigen::MatrixXd H_, E_, WAs_, Wsel_, C_;
  Eigen::VectorXd g_, bE_, c_lo_, c_up_, x_lo_, x_up_, res_;
  // null-space reduction (levels >= 1): x = x_{k-1}* + Z y, Z = Zd (Z_[cur_], n_dense_ x nzd_) on the dense
  // variables and unit columns on the free ones (no row above touches them), so nz_ = nzd_ + n_free_
  NullSpace null_space_;
  Eigen::MatrixXd Z_[2], B_, HZ_, Hy_, Cy_, Ad_, Cd_;
  int cur_ = 0, nz_ = 0, nzd_ = 0;
  Eigen::VectorXd gy_, ylo_, yup_, tmp_, xd_, blo_, bup_;
  std::vector<int> dense_;    // the variable of Zd's row i (n_dense_ of them)
  std::vector<int> free_;     // the free variables (n_free_)
  std::vector<int> touched_;  // the free variables the current level touches (n_touched_)
  int n_dense_ = 0, n_free_ = 0, n_touched_ = 0;
  bool dense_identity_ = false;  // dense_ = 0, 1, ..., n-1
  std::vector<int> nz_idx_;  // a row's nonzero touched-free columns and their values (addDiagonalTerm)
  Eigen::VectorXd nz_val_, w_;
  // separable touched variables (closed form) and the QP of the others, compacted
  std::vector<int> kept_, sep_;
  // level 0's independent row blocks (firstNullSpace)
  std::vector<int> block_root_, block_cols_, block_rows_, row_block_;
  Eigen::MatrixXd Ab_;
  Eigen::MatrixXd Hc_, Cc_;
  Eigen::VectorXd gc_, blc_, buc_, ysol_;
  std::vector<int> level_rank_;
  std::vector<int> used_;  // level 0: the columns touched by its rows or by a constraint row (n_used_ of them)
  int n_used_ = 0;
  double rank_tol_ = 1e-10;  // relative pivot threshold of the rank-revealing QR
  int failed_level_ = -1;
};

}  // namespace centaur
