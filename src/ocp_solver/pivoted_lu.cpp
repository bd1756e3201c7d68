#include "ocp_solver/pivoted_lu.hpp"

#include <cmath>
#include <utility>

#include "common/eigen_empty.hpp"

namespace centaur::ocp_solver {

void PivotedLu::compute(const Eigen::Ref<const Eigen::MatrixXd>& m, double tol) {
  lu_ = m;
  const int rows = static_cast<int>(m.rows()), cols = static_cast<int>(m.cols());
  row_perm_.resize(rows);
  col_perm_.resize(cols);
  for (int i = 0; i < rows; ++i) row_perm_[i] = i;
  for (int j = 0; j < cols; ++j) col_perm_[j] = j;
  rank_ = 0;
  const int steps = std::min(rows, cols);
  for (int k = 0; k < steps; ++k) {
    Eigen::Index pi = 0, pj = 0;
    const double pivot = lu_.bottomRightCorner(rows - k, cols - k).cwiseAbs().maxCoeff(&pi, &pj);
    if (!(pivot > tol)) break;  // also stops on NaN
    pi += k;
    pj += k;
    if (pi != k) {
      lu_.row(k).swap(lu_.row(pi));
      std::swap(row_perm_[k], row_perm_[pi]);
    }
    if (pj != k) {
      lu_.col(k).swap(lu_.col(pj));
      std::swap(col_perm_[k], col_perm_[pj]);
    }
    const double inv = 1.0 / lu_(k, k);
    lu_.col(k).tail(rows - k - 1) *= inv;
    lu_.bottomRightCorner(rows - k - 1, cols - k - 1).noalias() -=
        lu_.col(k).tail(rows - k - 1) * lu_.row(k).tail(cols - k - 1);
    ++rank_;
  }
}

void PivotedLu::applyRowTransform(Eigen::Ref<Eigen::MatrixXd> y) const {
  const int r = rank_, rows = static_cast<int>(lu_.rows());
  if (r == 0) return;
  solveInPlaceUnlessEmpty(lu_.topLeftCorner(r, r).triangularView<Eigen::UnitLower>(), y.topRows(r));
  if (rows > r) y.bottomRows(rows - r).noalias() -= lu_.bottomLeftCorner(rows - r, r) * y.topRows(r);
}

void PivotedLu::applyRowTransformTransposed(Eigen::Ref<Eigen::VectorXd> y) const {
  const int r = rank_, rows = static_cast<int>(lu_.rows());
  if (r == 0) return;
  if (rows > r) y.head(r).noalias() -= lu_.bottomLeftCorner(rows - r, r).transpose() * y.tail(rows - r);
  solveInPlaceUnlessEmpty(lu_.topLeftCorner(r, r).triangularView<Eigen::UnitLower>().transpose(), y.head(r));
}

}  // namespace centaur::ocp_solver
