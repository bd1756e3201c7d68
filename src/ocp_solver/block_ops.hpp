#pragma once
// Small dense and sparse block operations of the Riccati recursion (riccati.cpp), written as column sweeps over
// column-major storage. Each one computes every entry with the same operations in the same order as the plain
// (row-wise or Eigen) formulation it replaces, so the factors are bit-identical to it.
#include <Eigen/Core>

#include <vector>

namespace centaur::ocp_solver {

/// A sparse matrix by columns (compressed sparse columns), its storage reused between fills.
struct SparseColumns {
  int rows = 0, cols = 0;
  std::vector<int> start;  ///< column j holds entries start[j] .. start[j+1]-1
  std::vector<int> row;
  std::vector<double> value;
};

/// out = [A B] (A and B with `rows` rows), exact zeros dropped, each column's entries in row order.
void sparseColumns(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, int rows, SparseColumns& out);
/// out(i, j) = in(perm[i], perm[j]); the first `identity_head` entries of perm must be 0, 1, 2, ... In the first
/// `lower_cols` columns only the entries on and below the diagonal are written (the rest keep what they held).
void permuteSymmetric(const Eigen::MatrixXd& in, const std::vector<int>& perm, int identity_head, Eigen::MatrixXd& out,
                      int lower_cols = 0);
/// out = the first `cols` columns of `in`, rows in the order `rows` (out(i, j) = in(rows[i], j)).
void gatherRows(const Eigen::MatrixXd& in, const std::vector<int>& rows, int cols, Eigen::MatrixXd& out);
/// Scale each row of `a` to largest |entry| 1 (rows of zeros, and rows with a NaN, unscaled); scale[i] = the factor.
void equilibrateRows(Eigen::MatrixXd& a, Eigen::VectorXd& scale);

/// y += S_J x, J = the columns col0 .. col0 + x.size() - 1 of S: each entry's products summed in column order (in
/// `t`, S.rows entries), then added to y. These are the sums of Eigen's column-major matrix-vector product with the
/// dense matrix (its zero products change no sum), so y gets that product's bits.
void sparseColsTimesAdd(const SparseColumns& S, int col0, const Eigen::VectorXd& x, Eigen::VectorXd& t, double* y);
/// y[j] += S(:, col0 + j)' x for j < n (x with S.rows entries): each dot product summed as Eigen's row-major
/// matrix-vector product sums it with the dense matrix. With two-lane packets (SSE2) that is the even and the odd
/// rows apart, then the two lanes, then an odd last row; without vectorization in row order. Other packet widths
/// (e.g. AVX builds) get the plain row-order sum, which may round differently from Eigen's product.
/// Needs each column's entries in row order.
void sparseColsTransposedTimesAdd(const SparseColumns& S, int col0, int n, const Eigen::VectorXd& x, double* y);

/// out = D S (add: out += D S) for a dense D and a sparse S: out.col(j) += S(k, j) D.col(k) over the nonzeros of
/// column j in row order (the sums of Eigen's dense-times-sparse product). With `perm`, S's columns are taken in
/// that order (column j of the product from column perm[j] of S). In the first `lower_cols` columns only the rows
/// from the diagonal down are computed (the entries above keep what they held).
/// Blocks of kRows rows of a column are accumulated in registers over all of the column's nonzeros and stored once:
/// each entry still gets its products added one after the other, in the same order, so the bits are those of an
/// axpy per nonzero, without reloading and storing the column for each one.
template <class Out>
void denseTimesSparse(const Eigen::MatrixXd& D, const SparseColumns& S, Out&& out, bool add,
                      const std::vector<int>* perm = nullptr, int lower_cols = 0) {
  constexpr int kRows = 8;
  using Block = Eigen::Matrix<double, kRows, 1>;
  const Eigen::Index rows = D.rows();
  const double* d = D.data();
  for (int j = 0; j < S.cols; ++j) {
    const int c = perm ? (*perm)[j] : j;
    const int p0 = S.start[c], p1 = S.start[c + 1];
    double* o = out.col(j).data();
    Eigen::Index i = j < lower_cols ? j : 0;
    for (; i + kRows <= rows; i += kRows) {
      Block acc = add ? Block(Eigen::Map<const Block>(o + i)) : Block::Zero();
      for (int p = p0; p < p1; ++p) acc += S.value[p] * Eigen::Map<const Block>(d + S.row[p] * rows + i);
      Eigen::Map<Block>(o + i) = acc;
    }
    for (; i < rows; ++i) {
      double acc = add ? o[i] : 0.0;
      for (int p = p0; p < p1; ++p) acc += S.value[p] * d[S.row[p] * rows + i];
      o[i] = acc;
    }
  }
}

}  // namespace centaur::ocp_solver
