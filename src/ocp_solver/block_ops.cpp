#include "ocp_solver/block_ops.hpp"

#include <algorithm>
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

void sparseColsTimesAdd(const SparseColumns& S, int col0, const Eigen::VectorXd& x, Eigen::VectorXd& t, double* y) {
  t.setZero(S.rows);
  double* __restrict acc = t.data();
  const int n = static_cast<int>(x.size());
  for (int j = 0; j < n; ++j) {
    const double xj = x[j];
    for (int p = S.start[col0 + j]; p < S.start[col0 + j + 1]; ++p) acc[S.row[p]] += S.value[p] * xj;
  }
  for (int i = 0; i < S.rows; ++i) y[i] += acc[i];
}

void sparseColsTransposedTimesAdd(const SparseColumns& S, int col0, int n, const Eigen::VectorXd& x, double* y) {
  // Eigen's row-major kernel: lanes of packet width L over the rows below the last full packet, their sum, then
  // the remaining rows in order.
  constexpr int kLanes = Eigen::internal::packet_traits<double>::Vectorizable
                             ? Eigen::internal::packet_traits<double>::size : 1;
  constexpr int L = kLanes == 2 ? 2 : 1;
  const int packed = S.rows - S.rows % L;
  for (int j = 0; j < n; ++j) {
    double lane[2] = {0.0, 0.0};
    int p = S.start[col0 + j];
    const int end = S.start[col0 + j + 1];
    for (; p < end && S.row[p] < packed; ++p) lane[S.row[p] % L] += S.value[p] * x[S.row[p]];
    double sum = L == 2 ? lane[0] + lane[1] : lane[0];
    for (; p < end; ++p) sum += S.value[p] * x[S.row[p]];
    y[j] += sum;
  }
}

void permuteSymmetric(const Eigen::MatrixXd& in, const std::vector<int>& perm, int identity_head, Eigen::MatrixXd& out,
                      int lower_cols) {
  const int n = static_cast<int>(perm.size());
  out.resize(n, n);
  for (int j = 0; j < n; ++j) {
    const double* __restrict src = in.col(perm[j]).data();
    double* __restrict dst = out.col(j).data();
    const int i0 = j < lower_cols ? j : 0;
    for (int i = i0; i < identity_head; ++i) dst[i] = src[i];
    for (int i = std::max(i0, identity_head); i < n; ++i) dst[i] = src[perm[i]];
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
