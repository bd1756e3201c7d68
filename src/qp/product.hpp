#pragma once
// Matrix products that never touch the heap. Eigen's GEMM packs a block of the left operand (rows x depth) and
// of the right one (depth x cols) into buffers that live on the stack only up to EIGEN_STACK_ALLOCATION_LIMIT
// (128 KB); larger products (e.g. 200 constraint rows x 100 variables) would call malloc. Splitting the product
// into tiles of at most kTile doubles per packed operand keeps every buffer on the stack.
#include <Eigen/Core>

#include <algorithm>

namespace centaur {

/// dst = lhs * rhs (accumulate == false) or dst += lhs * rhs, tile by tile. dst must not alias lhs or rhs.
template <class Dst, class Lhs, class Rhs>
void productNoAlloc(Dst&& dst, const Lhs& lhs, const Rhs& rhs, bool accumulate) {
  constexpr Eigen::Index kTile = 12000;  // doubles per packed operand (96 KB < 128 KB)
  const Eigen::Index rows = lhs.rows(), cols = rhs.cols(), depth = lhs.cols();
  const Eigen::Index step = std::max<Eigen::Index>(8, kTile / std::max<Eigen::Index>(depth, 1));
  for (Eigen::Index r0 = 0; r0 < rows; r0 += step) {
    const Eigen::Index rr = std::min(step, rows - r0);
    for (Eigen::Index c0 = 0; c0 < cols; c0 += step) {
      const Eigen::Index cc = std::min(step, cols - c0);
      auto d = dst.block(r0, c0, rr, cc);
      if (accumulate) {
        d.noalias() += lhs.middleRows(r0, rr) * rhs.middleCols(c0, cc);
      } else {
        d.noalias() = lhs.middleRows(r0, rr) * rhs.middleCols(c0, cc);
      }
    }
  }
}

}  // namespace centaur
