// ctest-labels: unit
// The complete-pivoting LU that splits a stage's rows into independent and dependent ones (pivoted_lu.hpp):
// it reproduces the matrix (P M Q = L U), finds the numerical rank of rank-deficient matrices, its row
// transformation zeroes exactly the dependent rows, the transposed transformation is its adjoint, and the
// pivot order is the one of a plain search for the largest entry (the first one in column-major order on ties).
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <limits>
#include <random>

#include "ocp_solver/pivoted_lu.hpp"

using centaur::ocp_solver::PivotedLu;

namespace {

Eigen::MatrixXd randomMatrix(int rows, int cols, std::mt19937& rng) {
  std::normal_distribution<double> d(0.0, 1.0);
  Eigen::MatrixXd m(rows, cols);
  for (int j = 0; j < cols; ++j)
    for (int i = 0; i < rows; ++i) m(i, j) = d(rng);
  return m;
}

// P M Q from the permutations.
Eigen::MatrixXd permuted(const Eigen::MatrixXd& m, const PivotedLu& lu) {
  Eigen::MatrixXd out(m.rows(), m.cols());
  for (int j = 0; j < m.cols(); ++j)
    for (int i = 0; i < m.rows(); ++i) out(i, j) = m(lu.rowPerm()[i], lu.colPerm()[j]);
  return out;
}

// The reference pivot sequence: at every step the largest |entry| of the remaining block (first in
// column-major order), with the elimination done by dense Eigen operations.
std::vector<std::pair<int, int>> referencePivots(Eigen::MatrixXd a, double tol) {
  std::vector<std::pair<int, int>> piv;
  const int rows = static_cast<int>(a.rows()), cols = static_cast<int>(a.cols());
  for (int k = 0; k < std::min(rows, cols); ++k) {
    Eigen::Index i = 0, j = 0;
    if (!(a.bottomRightCorner(rows - k, cols - k).cwiseAbs().maxCoeff(&i, &j) > tol)) break;
    i += k;
    j += k;
    piv.push_back({static_cast<int>(i), static_cast<int>(j)});
    a.row(k).swap(a.row(i));
    a.col(k).swap(a.col(j));
    a.col(k).tail(rows - k - 1) *= 1.0 / a(k, k);
    a.bottomRightCorner(rows - k - 1, cols - k - 1) -= a.col(k).tail(rows - k - 1) * a.row(k).tail(cols - k - 1);
  }
  return piv;
}

}  // namespace

TEST(PivotedLu, ReproducesTheMatrixAndFindsTheRankOfRankDeficientMatrices) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 200; ++trial) {
    const int rows = 1 + static_cast<int>(rng() % 12), cols = 1 + static_cast<int>(rng() % 12);
    const int rank = static_cast<int>(rng() % (std::min(rows, cols) + 1));
    const Eigen::MatrixXd m = randomMatrix(rows, rank, rng) * randomMatrix(rank, cols, rng);
    PivotedLu lu;
    lu.compute(m, 1e-10 * std::max(1.0, m.cwiseAbs().maxCoeff()));
    ASSERT_EQ(lu.rank(), rank) << rows << "x" << cols;
    const int r = lu.rank();
    const Eigen::MatrixXd& f = lu.packed();
    Eigen::MatrixXd L = Eigen::MatrixXd::Zero(rows, r), U = Eigen::MatrixXd::Zero(r, cols);
    for (int k = 0; k < r; ++k) {
      L(k, k) = 1.0;
      L.col(k).tail(rows - k - 1) = f.col(k).tail(rows - k - 1);
      U.row(k).tail(cols - k) = f.row(k).tail(cols - k);
    }
    // Beyond the rank the remaining block is (numerically) zero, so L U is the whole matrix.
    EXPECT_LE((permuted(m, lu) - L * U).cwiseAbs().maxCoeff(), 1e-12 * std::max(1.0, m.cwiseAbs().maxCoeff()));
  }
}

TEST(PivotedLu, RowTransformZeroesTheDependentRowsAndItsTransposeIsTheAdjoint) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 100; ++trial) {
    const int rows = 2 + static_cast<int>(rng() % 10), cols = 2 + static_cast<int>(rng() % 10);
    const int rank = 1 + static_cast<int>(rng() % (std::min(rows, cols) - 1));
    const Eigen::MatrixXd m = randomMatrix(rows, rank, rng) * randomMatrix(rank, cols, rng);
    PivotedLu lu;
    lu.compute(m, 1e-10 * m.cwiseAbs().maxCoeff());
    ASSERT_EQ(lu.rank(), rank);
    // The transformation applied to P M Q: the independent rows become U, the dependent ones vanish.
    Eigen::MatrixXd t = permuted(m, lu);
    lu.applyRowTransform(t);
    EXPECT_LE(t.bottomRows(rows - rank).cwiseAbs().maxCoeff(), 1e-12 * m.cwiseAbs().maxCoeff());
    // <T a, b> = <a, T' b> for random vectors.
    const Eigen::VectorXd a = randomMatrix(rows, 1, rng), b = randomMatrix(rows, 1, rng);
    Eigen::MatrixXd ta = a;
    lu.applyRowTransform(ta);
    Eigen::VectorXd tb = b;
    lu.applyRowTransformTransposed(tb);
    EXPECT_NEAR(ta.col(0).dot(b), a.dot(tb), 1e-10 * (1.0 + std::abs(a.dot(tb))));
  }
}

TEST(PivotedLu, PivotsAreTheLargestRemainingEntriesFirstOnTies) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 100; ++trial) {
    const int rows = 1 + static_cast<int>(rng() % 9), cols = 1 + static_cast<int>(rng() % 9);
    Eigen::MatrixXd m = randomMatrix(rows, cols, rng);
    if (trial % 2 == 0) m = m.array().round();  // small integers: many ties and exact zeros
    PivotedLu lu;
    lu.compute(m, 1e-10);
    const auto ref = referencePivots(m, 1e-10);
    ASSERT_EQ(lu.rank(), static_cast<int>(ref.size()));
    // Replaying the reference swaps on the identity permutations gives the solver's permutations.
    std::vector<int> rp(rows), cp(cols);
    for (int i = 0; i < rows; ++i) rp[i] = i;
    for (int j = 0; j < cols; ++j) cp[j] = j;
    for (int k = 0; k < static_cast<int>(ref.size()); ++k) {
      std::swap(rp[k], rp[ref[k].first]);
      std::swap(cp[k], cp[ref[k].second]);
    }
    EXPECT_EQ(lu.rowPerm(), rp);
    EXPECT_EQ(lu.colPerm(), cp);
  }
}

TEST(PivotedLu, ZeroAndNanMatricesHaveRankZero) {
  PivotedLu lu;
  lu.compute(Eigen::MatrixXd::Zero(3, 4), 1e-10);
  EXPECT_EQ(lu.rank(), 0);
  Eigen::MatrixXd m = Eigen::MatrixXd::Ones(3, 3);
  m(0, 0) = std::numeric_limits<double>::quiet_NaN();
  lu.compute(m, 1e-10);
  EXPECT_EQ(lu.rank(), 0);  // a NaN first entry stops the factorization instead of pivoting on it
  lu.compute(Eigen::MatrixXd(0, 5), 1e-10);
  EXPECT_EQ(lu.rank(), 0);
}
