#include "sim/compare_pitch.hpp"

#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "common/error.hpp"

namespace centaur::sim {

double pitchFromQuaternion(double w, double x, double y, double z) {
  const double n2 = w * w + x * x + y * y + z * z;
  if (!(n2 > 0.0) || !std::isfinite(n2)) return std::nan("");
  return std::asin(std::clamp(2.0 * (w * y - x * z) / n2, -1.0, 1.0));
}

namespace {

/// Closes an HDF5 handle on scope exit.
struct H5Handle {
  hid_t id;
  herr_t (*close)(hid_t);
  H5Handle(hid_t i, herr_t (*c)(hid_t)) : id(i), close(c) {}
  H5Handle(const H5Handle&) = delete;
  H5Handle& operator=(const H5Handle&) = delete;
  ~H5Handle() {
    if (id >= 0) close(id);
  }
};

/// Silences HDF5's automatic error printing in this thread while alive (errors become InputError).
class QuietHdf5 {
 public:
  QuietHdf5() {
    H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  QuietHdf5(const QuietHdf5&) = delete;
  QuietHdf5& operator=(const QuietHdf5&) = delete;
  ~QuietHdf5() { H5Eset_auto2(H5E_DEFAULT, func_, data_); }

 private:
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
};

/// Dataset `name` as doubles; `dims` receives its shape.
std::vector<double> readDoubles(hid_t file, const std::string& path, const std::string& name,
                                std::vector<hsize_t>& dims) {
  if (H5Lexists(file, name.c_str(), H5P_DEFAULT) <= 0) {
    throw InputError(path + ": dataset '" + name + "' is missing (not a centaur simulation log?)");
  }
  H5Handle ds(H5Dopen2(file, name.c_str(), H5P_DEFAULT), H5Dclose);
  if (ds.id < 0) throw InputError(path + ": dataset '" + name + "' cannot be opened");
  H5Handle space(H5Dget_space(ds.id), H5Sclose);
  const int rank = space.id >= 0 ? H5Sget_simple_extent_ndims(space.id) : -1;
  if (rank < 1) throw InputError(path + ": dataset '" + name + "' has no readable shape");
  dims.assign(static_cast<std::size_t>(rank), 0);
  H5Sget_simple_extent_dims(space.id, dims.data(), nullptr);
  hsize_t total = 1;
  for (hsize_t d : dims) total *= d;
  std::vector<double> out(static_cast<std::size_t>(total));
  if (total > 0 && H5Dread(ds.id, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0) {
    throw InputError(path + ": dataset '" + name + "' cannot be read (corrupt or not numeric)");
  }
  return out;
}

}  // namespace

PitchSeries readLogPitch(const std::string& log_path, const std::string& quat_dataset) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(log_path, ec)) throw InputError(log_path + ": no such simulation log");
  const QuietHdf5 quiet;
  H5Handle file(H5Fopen(log_path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (file.id < 0) throw InputError(log_path + ": not an HDF5 file or corrupt");
  std::vector<hsize_t> tdims, qdims;
  const std::vector<double> t = readDoubles(file.id, log_path, "t", tdims);
  const std::vector<double> q = readDoubles(file.id, log_path, quat_dataset, qdims);
  if (tdims.size() != 1) throw InputError(log_path + ": dataset 't' must be one-dimensional (N)");
  if (qdims.size() != 2 || qdims[0] != tdims[0] || qdims[1] != 4) {
    throw InputError(log_path + ": dataset '" + quat_dataset + "' must have shape (N, 4) with N = " +
                     std::to_string(tdims[0]) + " samples of 't'");
  }
  PitchSeries s;
  s.t = t;
  s.pitch_deg.resize(t.size());
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double* r = &q[4 * k];
    s.pitch_deg[k] = pitchFromQuaternion(r[0], r[1], r[2], r[3]) * 180.0 / M_PI;
  }
  return s;
}

}  // namespace centaur::sim
