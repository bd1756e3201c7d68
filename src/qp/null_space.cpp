#include "qp/null_space.hpp"

#include <Eigen/Householder>

#include <algorithm>
#include <cmath>

namespace centaur {

void NullSpace::reserve(int m_max, int p_max) {
  M_.setZero(std::max(p_max, 1), std::max(m_max, 1));
  N_.setZero(std::max(p_max, 1), std::max(p_max, 1));
  tau_.setZero(std::max(std::min(m_max, p_max), 1));
  work_.setZero(std::max(std::max(m_max, p_max), 1));
  p_ = 0;
  rank_ = 0;
}

int NullSpace::compute(const Eigen::Ref<const Eigen::MatrixXd>& B, double tol, double scale) {
  const int m = static_cast<int>(B.rows());
  const int p = static_cast<int>(B.cols());
  p_ = p;
  rank_ = 0;
  auto M = M_.topLeftCorner(p, m);
  M = B.transpose();
  double max_norm = 0.0;
  for (int c = 0; c < m; ++c) max_norm = std::max(max_norm, M.col(c).norm());
  if (scale > 0.0) max_norm = scale;
  const int steps = std::min(p, m);
  for (int j = 0; j < steps && max_norm > 0.0; ++j) {
    // Pivot: the column with the largest norm in the rows not yet reduced.
    int best = j;
    double best_sq = -1.0;
    for (int c = j; c < m; ++c) {
      const double sq = M.col(c).tail(p - j).squaredNorm();
      if (sq > best_sq) {
        best_sq = sq;
        best = c;
      }
    }
    if (!(std::sqrt(best_sq) > tol * max_norm)) break;
    if (best != j) M.col(j).swap(M.col(best));
    double beta;
    M.col(j).tail(p - j).makeHouseholderInPlace(tau_[j], beta);
    M(j, j) = beta;
    if (j + 1 < m) {
      auto rest = M.block(j, j + 1, p - j, m - j - 1);
      rest.applyHouseholderOnTheLeft(M.col(j).tail(p - j - 1), tau_[j], work_.data());
    }
    ++rank_;
  }
  // Basis: Q(:, rank:p) = H_0 H_1 ... H_{rank-1} [0; I].
  auto N = N_.topLeftCorner(p, p - rank_);
  N.setZero();
  N.bottomRows(p - rank_).setIdentity();
  for (int i = rank_ - 1; i >= 0; --i) {
    auto rows = N.bottomRows(p - i);
    rows.applyHouseholderOnTheLeft(M.col(i).tail(p - i - 1), tau_[i], work_.data());
  }
  return rank_;
}

}  // namespace centaur
