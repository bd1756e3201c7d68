// ctest-labels: unit
// The small block kernels of the Riccati recursion (block_ops.hpp) against the dense Eigen expressions they
// replace: the products with the sparse dynamics give the dense products' bits (so the recursion's results do not
// depend on which one it uses), and the lower-triangle variants of the stage-matrix assembly compute the same
// entries on and below the diagonal and leave the others alone.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "ocp_solver/block_ops.hpp"

using namespace centaur::ocp_solver;

namespace {

constexpr int kLanes = Eigen::internal::packet_traits<double>::Vectorizable
                           ? Eigen::internal::packet_traits<double>::size : 1;

// A sparse [A B] of `rows` rows: column j has a number of nonzeros between 0 and 6 (at random rows), with values
// over sixteen orders of magnitude and both signs, so that sums in another order round differently.
Eigen::MatrixXd sparseDynamics(int rows, int cols, std::mt19937& rng) {
  std::uniform_int_distribution<int> count(0, 6), row(0, rows - 1), expo(-8, 8);
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(rows, cols);
  for (int j = 0; j < cols; ++j) {
    const int c = count(rng);
    for (int t = 0; t < c; ++t) m(row(rng), j) = n(rng) * std::pow(10.0, expo(rng));
  }
  return m;
}

Eigen::VectorXd wideVector(int n, std::mt19937& rng) {
  std::uniform_int_distribution<int> expo(-8, 8);
  std::normal_distribution<double> d(0.0, 1.0);
  Eigen::VectorXd v(n);
  for (int i = 0; i < n; ++i) v[i] = d(rng) * std::pow(10.0, expo(rng));
  return v;
}

// How many entries differ in their bits (== on doubles; no signed zeros or NaNs arise here).
int bitsDiffer(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  int d = 0;
  for (int i = 0; i < a.size(); ++i) d += !(a[i] == b[i]);
  return d;
}

// The bits of the dense product with SSE2 (the baseline build) or without vectorization; other builds (AVX, FMA)
// sum in other orders or fuse operations, so there only the values are compared.
void expectSameProduct(const Eigen::VectorXd& dense, const Eigen::VectorXd& sparse, int trial) {
  if (kLanes <= 2) {
    EXPECT_EQ(bitsDiffer(dense, sparse), 0) << "trial " << trial;
  } else {
    EXPECT_LT((dense - sparse).cwiseAbs().maxCoeff(), 1e-12 * (1.0 + dense.cwiseAbs().maxCoeff())) << "trial " << trial;
  }
}

TEST(BlockOps, SparseDynamicsProductsGiveTheBitsOfTheDenseOnes) {
  std::mt19937 rng(7);
  int rounding_sensitive = 0;  // entries where a plain row-order sum rounds differently from Eigen's product
  for (int trial = 0; trial < 200; ++trial) {
    const int rows = 1 + trial % 61, nx = 1 + (trial * 7) % 57, nu = 1 + (trial * 3) % 33;
    const Eigen::MatrixXd A = sparseDynamics(rows, nx, rng), B = sparseDynamics(rows, nu, rng);
    SparseColumns M;
    sparseColumns(A, B, rows, M);
    const Eigen::VectorXd x = wideVector(nx, rng), u = wideVector(nu, rng), w = wideVector(rows, rng);

    // x_next = b + A x + B u, as the forward pass forms it.
    const Eigen::VectorXd b = wideVector(rows, rng);
    Eigen::VectorXd dense = b, sparse = b, t;
    dense.noalias() += A * x;
    dense.noalias() += B * u;
    sparseColsTimesAdd(M, 0, x, t, sparse.data());
    sparseColsTimesAdd(M, nx, u, t, sparse.data());
    expectSameProduct(dense, sparse, trial);

    // q += [A B]' w, as the backward pass forms it.
    const Eigen::VectorXd h = wideVector(nx + nu, rng);
    Eigen::VectorXd qd = h, qs = h;
    qd.head(nx).noalias() += A.transpose() * w;
    qd.tail(nu).noalias() += B.transpose() * w;
    sparseColsTransposedTimesAdd(M, 0, nx, w, qs.data());
    sparseColsTransposedTimesAdd(M, nx, nu, w, qs.data() + nx);
    expectSameProduct(qd, qs, trial);
    Eigen::VectorXd plain = h;
    for (int j = 0; j < nx + nu; ++j) {
      double s = 0.0;
      for (int p = M.start[j]; p < M.start[j + 1]; ++p) s += M.value[p] * w[M.row[p]];
      plain[j] += s;
    }
    rounding_sensitive += bitsDiffer(qd, plain);
  }
  // The data do distinguish summation orders: the lane order above is the one that matches.
  if (kLanes == 2) {
    EXPECT_GT(rounding_sensitive, 50);
  }
}

// The pull-back's dense-times-sparse product, accumulated in register blocks of rows, against Eigen's product of a
// dense and a sparse matrix: the same bits, for row counts around and between the blocks, overwritten and added to.
TEST(BlockOps, DenseTimesSparseGivesTheBitsOfEigensProduct) {
  std::mt19937 rng(5);
  int rounding_sensitive = 0;  // entries where the products summed in reverse order round differently
  for (int trial = 0; trial < 120; ++trial) {
    const int rows = 1 + trial % 41, nx = 1 + (trial * 7) % 23, nu = 1 + (trial * 3) % 13, n_all = nx + nu;
    const Eigen::MatrixXd A = sparseDynamics(rows, nx, rng), B = sparseDynamics(rows, nu, rng);
    SparseColumns M;
    sparseColumns(A, B, rows, M);
    Eigen::MatrixXd D(rows, rows), C(rows, n_all);
    for (int j = 0; j < rows; ++j) D.col(j) = wideVector(rows, rng);
    for (int j = 0; j < n_all; ++j) C.col(j) = wideVector(rows, rng);
    Eigen::MatrixXd AB(rows, n_all);
    AB << A, B;
    const Eigen::SparseMatrix<double> S = AB.sparseView(0.0, 0.0);

    Eigen::MatrixXd expected = D * S, got(rows, n_all);
    denseTimesSparse(D, M, got, false);
    EXPECT_TRUE((got.array() == expected.array()).all()) << "trial " << trial;
    Eigen::MatrixXd added = C;
    expected = C;
    expected.noalias() += D * S;
    denseTimesSparse(D, M, added, true);
    EXPECT_TRUE((added.array() == expected.array()).all()) << "trial " << trial;

    for (int j = 0; j < n_all; ++j)
      for (int i = 0; i < rows; ++i) {
        double reverse = 0.0;
        for (int p = M.start[j + 1] - 1; p >= M.start[j]; --p) reverse += M.value[p] * D(i, M.row[p]);
        rounding_sensitive += !(reverse == got(i, j));
      }
  }
  EXPECT_GT(rounding_sensitive, 50);  // the data do distinguish summation orders
}

TEST(BlockOps, LowerTriangleAssemblyComputesTheSameEntriesAndLeavesTheRest) {
  std::mt19937 rng(11);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int trial = 0; trial < 40; ++trial) {
    const int nx = 3 + trial % 9, nu = 2 + trial % 5, n_all = nx + nu, rows = 2 + trial % 7;
    Eigen::MatrixXd H(n_all, n_all), P(rows, rows);
    for (int j = 0; j < n_all; ++j)
      for (int i = 0; i < n_all; ++i) H(i, j) = n(rng);
    for (int j = 0; j < rows; ++j)
      for (int i = 0; i < rows; ++i) P(i, j) = n(rng);
    std::vector<int> perm(n_all);
    for (int i = 0; i < n_all; ++i) perm[i] = i;
    std::shuffle(perm.begin() + nx, perm.end(), rng);
    SparseColumns M;
    sparseColumns(sparseDynamics(rows, nx, rng), sparseDynamics(rows, nu, rng), rows, M);
    const int lower = 1 + trial % n_all;

    Eigen::MatrixXd full, part = Eigen::MatrixXd::Constant(n_all, n_all, 12345.0);
    permuteSymmetric(H, perm, nx, full);
    permuteSymmetric(H, perm, nx, part, lower);
    Eigen::MatrixXd PM(rows, n_all);  // M' P M as the recursion forms it: P M, transposed, times M
    denseTimesSparse(P, M, PM, false, &perm);
    const Eigen::MatrixXd D = PM.transpose();
    denseTimesSparse(D, M, full, true, &perm);
    denseTimesSparse(D, M, part, true, &perm, lower);
    for (int j = 0; j < n_all; ++j) {
      for (int i = 0; i < n_all; ++i) {
        if (j < lower && i < j) {
          EXPECT_EQ(part(i, j), 12345.0) << i << "," << j;
        } else {
          EXPECT_EQ(part(i, j), full(i, j)) << i << "," << j;
        }
      }
    }
  }
}

}  // namespace
