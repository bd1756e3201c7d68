// ctest-labels: unit
// Null-space basis by column-pivoted Householder QR: B N = 0, N'N = I, the rank of rank-deficient matrices,
// and one workspace reused for many sizes.
#include <gtest/gtest.h>

#include <random>

#include "qp/null_space.hpp"

using centaur::NullSpace;
using Eigen::MatrixXd;

TEST(NullSpace, BasisIsOrthonormalAndAnnihilatesB) {
  std::mt19937 rng(4);
  std::normal_distribution<double> N(0.0, 1.0);
  NullSpace ns;
  ns.reserve(60, 50);
  for (int trial = 0; trial < 300; ++trial) {
    const int p = 1 + trial % 50;
    const int m = 1 + (trial * 7) % 60;
    const int true_rank = std::min({p, m, 1 + (trial * 3) % 50});
    // B = U V' with U m x r, V p x r: rank r (almost surely)
    MatrixXd U(m, true_rank), V(p, true_rank);
    for (int i = 0; i < U.size(); ++i) U.data()[i] = N(rng);
    for (int i = 0; i < V.size(); ++i) V.data()[i] = N(rng);
    const MatrixXd B = U * V.transpose();
    const int rank = ns.compute(B, 1e-10);
    EXPECT_EQ(rank, true_rank) << "trial " << trial << " m " << m << " p " << p;
    const MatrixXd Nb = ns.basis();
    ASSERT_EQ(Nb.rows(), p);
    ASSERT_EQ(Nb.cols(), p - rank);
    if (Nb.cols() == 0) continue;
    EXPECT_LT((B * Nb).cwiseAbs().maxCoeff(), 1e-12 * (1.0 + B.cwiseAbs().maxCoeff()) * p);
    EXPECT_LT((Nb.transpose() * Nb - MatrixXd::Identity(Nb.cols(), Nb.cols())).cwiseAbs().maxCoeff(), 1e-13);
  }
}

TEST(NullSpace, ZeroMatrixKeepsTheWholeSpace) {
  NullSpace ns;
  ns.reserve(3, 4);
  EXPECT_EQ(ns.compute(MatrixXd::Zero(3, 4), 1e-10), 0);
  EXPECT_LT((ns.basis() - MatrixXd::Identity(4, 4)).norm(), 1e-15);
}
