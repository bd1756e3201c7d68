#pragma once
// LU factorization with complete pivoting of a small dense block, P M Q = L U, stopped at the numerical rank:
// the first `rank` rows of P M are independent, the others are combinations of them (L's lower part says
// which). The Riccati recursion uses it to split the stage rows into the ones the stage's controls can satisfy
// and the ones passed back to the previous stage.
#include <Eigen/Core>

#include <vector>

namespace centaur::ocp_solver {

class PivotedLu {
 public:
  /// Factor m (rows x cols); pivots below `tol` (absolute, the rows are equilibrated by the caller) end it.
  void compute(const Eigen::Ref<const Eigen::MatrixXd>& m, double tol);

  int rank() const { return rank_; }
  int rows() const { return static_cast<int>(lu_.rows()); }
  int cols() const { return static_cast<int>(lu_.cols()); }
  /// Row permutation: row i of P M is row rowPerm()[i] of M; likewise columns.
  const std::vector<int>& rowPerm() const { return row_perm_; }
  const std::vector<int>& colPerm() const { return col_perm_; }
  /// Packed factors of P M Q: strictly lower part of the first `rank` columns is L (unit diagonal), the upper
  /// part of the first `rank` rows is U.
  const Eigen::MatrixXd& packed() const { return lu_; }

  /// y <- L1^{-1} y for the first `rank` rows of y (in P order), then the other rows y_D <- y_D - L2 y_I.
  /// Applies the row transformation that zeroes the dependent rows' part in M to any block with those rows.
  void applyRowTransform(Eigen::Ref<Eigen::MatrixXd> y) const;
  /// The transpose of applyRowTransform (for multipliers): y_I <- L1^{-T} (y_I - L2' y_D).
  void applyRowTransformTransposed(Eigen::Ref<Eigen::VectorXd> y) const;

 private:
  Eigen::MatrixXd lu_;
  std::vector<int> row_perm_, col_perm_;
  int rank_ = 0;
};

}  // namespace centaur::ocp_solver
