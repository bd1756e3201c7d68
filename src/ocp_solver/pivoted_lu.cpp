#include "ocp_solver/pivoted_lu.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "common/eigen_empty.hpp"

namespace centaur::ocp_solver {

namespace {

// Largest |entry| of the block (column-major scan, the first one on ties, as Eigen's maxCoeff).
double maxAbs(const Eigen::MatrixXd& a, int r0, int c0, int& pi, int& pj) {
  double best = std::abs(a(r0, c0));
  pi = r0;
  pj = c0;
  for (int j = c0; j < a.cols(); ++j)
    for (int i = (j == c0 ? r0 + 1 : r0); i < a.rows(); ++i) {
      const double v = std::abs(a(i, j));
      if (v > best) best = v, pi = i, pj = j;
    }
  return best;
}

}  // namespace

// The rank-one update of the trailing block also finds the next pivot (one pass over the block per step).
void PivotedLu::compute(const Eigen::Ref<const Eigen::MatrixXd>& m, double tol) {
  lu_ = m;
  const int rows = static_cast<int>(m.rows()), cols = static_cast<int>(m.cols());
  row_perm_.resize(rows);
  col_perm_.resize(cols);
  for (int i = 0; i < rows; ++i) row_perm_[i] = i;
  for (int j = 0; j < cols; ++j) col_perm_[j] = j;
  rank_ = 0;
  const int steps = std::min(rows, cols);
  if (steps == 0) return;
  int pi = 0, pj = 0;
  double pivot = maxAbs(lu_, 0, 0, pi, pj);
  for (int k = 0; k < steps; ++k) {
    if (!(pivot > tol)) break;  // also stops on NaN
    if (pi != k) {
      lu_.row(k).swap(lu_.row(pi));
      std::swap(row_perm_[k], row_perm_[pi]);
    }
    if (pj != k) {
      lu_.col(k).swap(lu_.col(pj));
      std::swap(col_perm_[k], col_perm_[pj]);
    }
    const double inv = 1.0 / lu_(k, k);
    double* lk = lu_.col(k).data();
    for (int i = k + 1; i < rows; ++i) lk[i] *= inv;
    ++rank_;
    if (k + 1 == steps) break;
    pivot = -1.0;
    for (int j = k + 1; j < cols; ++j) {
      double* cj = lu_.col(j).data();
      const double u = cj[k];
      for (int i = k + 1; i < rows; ++i) {
        cj[i] -= lk[i] * u;
        const double v = std::abs(cj[i]);
        if (v > pivot || (pivot < 0.0 && !(v == v))) pivot = v, pi = i, pj = j;
      }
    }
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
