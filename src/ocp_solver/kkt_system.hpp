#pragma once
// The linear system of one interior-point iteration after the bound multipliers and the slacks of the
// inequality rows are eliminated:
//
//   [ W + diag(d_x)    J'          ] [dx]   [r_x]
//   [ J               -diag(d_c)   ] [dy] = [r_c]
//
// W is the Lagrangian Hessian and J the constraint Jacobian in the NLP's sparse structure (SparsePattern), d_x the
// barrier diagonal plus the primal regularization, d_c >= 0 per row: the condensed slack term of an inequality row,
// or the dual regularization of an equality row. Fixed variables (lower bound == upper bound) are not unknowns:
// their dx is zero and their rows of the first block are ignored.
#include <Eigen/Core>

#include <vector>

#include "ocp_solver/stage_qp.hpp"

namespace centaur::ocp_solver {

/// Sparsity of the NLP: Jacobian entries (row, col) and the lower triangle (row >= col) of the Hessian.
struct SparsePattern {
  int n = 0, m = 0;
  std::vector<int> jac_rows, jac_cols;
  std::vector<int> hess_rows, hess_cols;
};

enum class KktStatus {
  kOk,             ///< inertia (n, m, 0): the step is a descent direction for the barrier problem
  kWrongInertia,   ///< the Hessian is not positive definite on the null space of the exact rows
  kSingular,       ///< the exact rows are linearly dependent
};

/// One solve: the right-hand side and where the solution goes.
struct KktSolve {
  const Eigen::VectorXd& rx;
  const Eigen::VectorXd& rc;
  Eigen::VectorXd& dx;
  Eigen::VectorXd& dy;
};

class KktSolver {
 public:
  virtual ~KktSolver() = default;
  /// Factor with the Hessian and Jacobian values (pattern order) and the diagonals (d_c > 0 turns a row into a
  /// penalty, d_c == 0 keeps it exact; see alwaysExactRows()).
  virtual KktStatus factor(const double* hess, const double* jac, const Eigen::VectorXd& dx,
                           const Eigen::VectorXd& dc) = 0;
  /// factor() again with the same Hessian and Jacobian (the same arrays, their values unchanged since the last
  /// factor()) and new diagonals, e.g. the next trial of an inertia correction. A solver may keep what depends on
  /// neither diagonal; the result is that of factor().
  virtual KktStatus refactor(const double* hess, const double* jac, const Eigen::VectorXd& dx,
                             const Eigen::VectorXd& dc) {
    return factor(hess, jac, dx, dc);
  }
  /// Solve with the last factorization; dx has size n (zero for fixed variables), dy size m.
  virtual void solve(const Eigen::VectorXd& rx, const Eigen::VectorXd& rc, Eigen::VectorXd& dx,
                     Eigen::VectorXd& dy) = 0;
  /// Two solves with the last factorization, with the results of solve(a) then solve(b); a solver may run them
  /// concurrently.
  virtual void solveTwo(const KktSolve& a, const KktSolve& b) {
    solve(a.rx, a.rc, a.dx, a.dy);
    solve(b.rx, b.rc, b.dx, b.dy);
  }
  /// Rows the solver keeps exact even when the caller asks for a dual regularization (d_c > 0 on an equality
  /// row), e.g. the dynamics of an OCP; empty for a solver that honours every d_c.
  virtual const std::vector<char>& alwaysExactRows() const = 0;
  /// Counts of the last factorization (of the solver's own system, which may carry internal rows).
  virtual Inertia inertia() const = 0;
};

}  // namespace centaur::ocp_solver
