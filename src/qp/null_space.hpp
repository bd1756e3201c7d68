#pragma once
// Orthonormal basis of the null space of a matrix B (m x p): Householder QR with column pivoting of B',
// B' P = Q R; the rank is the number of pivots whose remaining column norm exceeds tol * a scale (the largest
// row norm of B by default), and the basis is Q(:, rank:p). Works on a preallocated workspace: compute() never allocates,
// whatever m <= m_max and p <= p_max (Eigen's decompositions reallocate when the sizes change).
#include <Eigen/Core>

namespace centaur {

class NullSpace {
 public:
  /// Allocate for B with at most m_max rows and p_max columns.
  void reserve(int m_max, int p_max);
  /// Factorise B (m x p) and form the basis; returns the rank. A pivot counts when its remaining column norm
  /// exceeds tol * scale, scale = `scale` if > 0, else the largest row norm of B (pass the norm of the rows
  /// before a projection, so that rows projected to rounding noise are not taken as independent).
  /// No allocation.
  int compute(const Eigen::Ref<const Eigen::MatrixXd>& B, double tol, double scale = 0.0);
  int rank() const { return rank_; }
  /// p x (p - rank), orthonormal columns spanning {y : B y = 0}.
  Eigen::Block<const Eigen::MatrixXd> basis() const { return N_.topLeftCorner(p_, p_ - rank_); }

 private:
  Eigen::MatrixXd M_, N_;
  Eigen::VectorXd tau_, work_;
  int p_ = 0, rank_ = 0;
};

}  // namespace centaur
