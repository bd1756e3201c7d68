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

void permuteColumns(const SparseColumns& S, const std::vector<int>& perm, SparseColumns& out) {
  out.rows = S.rows;
  out.cols = static_cast<int>(perm.size());
  out.start.resize(out.cols + 1);
  const std::size_t nnz = static_cast<std::size_t>(S.start[S.cols]);
  if (out.row.size() < nnz) {
    out.row.resize(nnz);
    out.value.resize(nnz);
  }
  int p = 0;
  for (int j = 0; j < out.cols; ++j) {
    out.start[j] = p;
    for (int q = S.start[perm[j]]; q < S.start[perm[j] + 1]; ++q, ++p) {
      out.row[p] = S.row[q];
      out.value[p] = S.value[q];
    }
  }
  out.start[out.cols] = p;
}

void permuteSymmetric(const Eigen::MatrixXd& in, const std::vector<int>& perm, int identity_head, Eigen::MatrixXd& out) {
  const int n = static_cast<int>(perm.size());
  out.resize(n, n);
  for (int j = 0; j < n; ++j) {
    const double* src = in.col(perm[j]).data();
    double* dst = out.col(j).data();
    for (int i = 0; i < identity_head; ++i) dst[i] = src[i];
    for (int i = identity_head; i < n; ++i) dst[i] = src[perm[i]];
  }
}

void equilibrateRows(Eigen::MatrixXd& a, Eigen::VectorXd& scale) {
  const int m = static_cast<int>(a.rows()), n = static_cast<int>(a.cols());
  scale.setZero(m);
  for (int j = 0; j < n; ++j) {
    const double* col = a.col(j).data();
    for (int i = 0; i < m; ++i) {
      const double v = std::abs(col[i]);
      if (v > scale[i] || v != v) scale[i] = v;  // a NaN stays (later comparisons with it are false)
    }
  }
  for (int i = 0; i < m; ++i) scale[i] = scale[i] > 0.0 ? 1.0 / scale[i] : 1.0;
  for (int j = 0; j < n; ++j) a.col(j).array() *= scale.array();
}

}  // namespace centaur::ocp_solver
