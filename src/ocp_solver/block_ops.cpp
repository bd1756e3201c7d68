#include "ocp_solver/block_ops.hpp"

#include <cmath>

namespace centaur::ocp_solver {

// Branch-free compaction: every entry is written, the write position advances past the nonzeros only.
void sparseColumns(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, int rows, SparseColumns& out) {
  const int na = static_cast<int>(A.cols()), nb = static_cast<int>(B.cols());
  out.rows = rows;
  out.cols = na + nb;
  out.start.resize(out.cols + 1);
  const std::size_t cap = static_cast<std::size_t>(rows) * out.cols;
  if (out.row.size() < cap) {
    out.row.resize(cap);
    out.value.resize(cap);
  }
  int* row = out.row.data();
  double* value = out.value.data();
  int p = 0;
  for (int j = 0; j < out.cols; ++j) {
    out.start[j] = p;
    const double* col = j < na ? A.col(j).data() : B.col(j - na).data();
    for (int i = 0; i < rows; ++i) {
      row[p] = i;
      value[p] = col[i];
      p += col[i] != 0.0;
    }
  }
  out.start[out.cols] = p;
}

void permuteSymmetric(const Eigen::MatrixXd& in, const std::vector<int>& perm, int identity_head, Eigen::MatrixXd& out) {
  const int n = static_cast<int>(perm.size());
  out.resize(n, n);
  for (int j = 0; j < n; ++j) {
    const double* __restrict src = in.col(perm[j]).data();
    double* __restrict dst = out.col(j).data();
    for (int i = 0; i < identity_head; ++i) dst[i] = src[i];
    for (int i = identity_head; i < n; ++i) dst[i] = src[perm[i]];
  }
}

void gatherRows(const Eigen::MatrixXd& in, const std::vector<int>& rows, int cols, Eigen::MatrixXd& out) {
  const int m = static_cast<int>(rows.size());
  out.resize(m, cols);
  for (int j = 0; j < cols; ++j) {
    const double* __restrict src = in.col(j).data();
    double* __restrict dst = out.col(j).data();
    for (int i = 0; i < m; ++i) dst[i] = src[rows[i]];
  }
}

void equilibrateRows(Eigen::MatrixXd& a, Eigen::VectorXd& scale) {
  const int m = static_cast<int>(a.rows()), n = static_cast<int>(a.cols());
  scale.setZero(m);
  double* __restrict sc = scale.data();  // not aliased by the columns: the compiler keeps it out of their loads
  for (int j = 0; j < n; ++j) {
    const double* __restrict col = a.col(j).data();
    for (int i = 0; i < m; ++i) {
      const double v = std::abs(col[i]);
      sc[i] = (v > sc[i] || v != v) ? v : sc[i];  // a NaN stays (later comparisons with it are false)
    }
  }
  for (int i = 0; i < m; ++i) sc[i] = sc[i] > 0.0 ? 1.0 / sc[i] : 1.0;
  for (int j = 0; j < n; ++j) a.col(j).array() *= scale.array();
}

}  // namespace centaur::ocp_solver
