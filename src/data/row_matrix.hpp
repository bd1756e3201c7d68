#pragma once
// The row-major dynamic matrix every data format uses (rows = samples; same layout as the HDF5 datasets).
#include <Eigen/Core>

namespace centaur::data {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

}  // namespace centaur::data
