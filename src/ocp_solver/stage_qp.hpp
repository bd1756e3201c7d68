#pragma once
// The stage-wise equality-constrained QP that one Newton step of an interior-point method solves on a direct
// multiple-shooting OCP (inequalities and bounds already condensed into the Hessians by the barrier):
//
//   min  sum_k 1/2 z_k' H_k z_k + h_k' z_k                 z_k = [x_k; u_k], k = 0..N (u_N empty)
//   s.t. x_{k+1} = A_k x_k + B_k u_k + b_k                  k = 0..N-1   (dynamics)
//        C_k z_k + c_k = 0                                  k = 0..N     (stage rows: mixed, pure-state or pure-control)
//
// x_0 is a decision variable (a fixed initial state is a set of unit rows in C_0). Dimensions may differ from
// stage to stage. Multipliers follow the Lagrangian
//   sum_k [1/2 z'Hz + h'z + eta_k'(C_k z_k + c_k)] + sum_{k<N} lambda_k'(A_k x_k + B_k u_k + b_k - x_{k+1}).
#include <Eigen/Core>

#include <vector>

#include "ocp_solver/block_ops.hpp"

namespace centaur::ocp_solver {

struct StageQp {
  int nx = 0;          ///< state dimension of this stage
  int nu = 0;          ///< control dimension (0 at the last stage)
  Eigen::MatrixXd H;   ///< (nx+nu) x (nx+nu), symmetric (both triangles filled)
  Eigen::VectorXd h;   ///< nx+nu
  Eigen::MatrixXd A;   ///< nx_{k+1} x nx   (empty at the last stage)
  Eigen::MatrixXd B;   ///< nx_{k+1} x nu
  Eigen::VectorXd b;   ///< nx_{k+1}
  Eigen::MatrixXd C;   ///< m_k x (nx+nu), may have no rows
  Eigen::VectorXd c;   ///< m_k
  /// Optional: [A B] by sparse columns, exact zeros dropped and each column's entries in row order (as
  /// sparseColumns() gives it), from a caller that knows where the dynamics can be nonzero; left empty (0 columns),
  /// the factorization builds it from A and B. The factorization and the solves multiply by it instead of A and B.
  SparseColumns M;

  /// Size every block for these dimensions (nx_next = 0 at the last stage) and zero it; M is dropped (the
  /// factorization then builds it from A and B).
  void resize(int state, int control, int rows, int nx_next);
};

/// The right-hand side (h, b, c) of a StageQp without its matrices: solves that share one factorization (e.g.
/// concurrently) each bring their own.
struct StageRhs {
  Eigen::VectorXd h, b, c;
};

struct StageSolution {
  Eigen::VectorXd x, u;
  Eigen::VectorXd lambda;  ///< multiplier of the dynamics x_{k+1} = ... (nx_{k+1}; empty at the last stage)
  Eigen::VectorXd eta;     ///< multipliers of the stage rows C_k z_k + c_k = 0
};

/// Inertia of the KKT matrix [H J'; J 0]: the counts of positive, negative and zero eigenvalues.
struct Inertia {
  int positive = 0, negative = 0, zero = 0;
};

inline void StageQp::resize(int state, int control, int rows, int nx_next) {
  nx = state;
  nu = control;
  const int n = state + control;
  H.setZero(n, n);
  h.setZero(n);
  A.setZero(nx_next, state);
  B.setZero(nx_next, control);
  b.setZero(nx_next);
  C.setZero(rows, n);
  c.setZero(rows);
  M = SparseColumns{};
}

}  // namespace centaur::ocp_solver
