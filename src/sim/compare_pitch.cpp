#include "sim/compare_pitch.hpp"

#include <algorithm>
#include <cmath>

#include "data/hdf5.hpp"

namespace centaur::sim {

double pitchFromQuaternion(double w, double x, double y, double z) {
  const double n2 = w * w + x * x + y * y + z * z;
  if (!(n2 > 0.0) || !std::isfinite(n2)) return std::nan("");
  return std::asin(std::clamp(2.0 * (w * y - x * z) / n2, -1.0, 1.0));
}

PitchSeries readLogPitch(const std::string& log_path, const std::string& quat_dataset) {
  const data::h5::Reader r(log_path, "a simulation log written by `centaur simulate --out`");
  std::vector<hsize_t> tdims, qdims;
  const std::vector<double> t = r.doubles(r.file(), "t", "t", {0}, tdims);
  const std::vector<double> q = r.doubles(r.file(), quat_dataset, quat_dataset, {tdims[0], 4}, qdims);
  PitchSeries s;
  s.t = t;
  s.pitch_deg.resize(t.size());
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double* row = &q[4 * k];
    s.pitch_deg[k] = pitchFromQuaternion(row[0], row[1], row[2], row[3]) * 180.0 / M_PI;
  }
  return s;
}

}  // namespace centaur::sim
