#pragma once
// The structured half of the HDF5 fuzz targets: the input bytes drive a generator that writes a file of one of
// the formats (primitive, arm trajectory, simulation log) into memory with HDF5's own writer: the datasets and
// attributes the format names, with shapes, types and values chosen by the input, mostly valid and sometimes not
// (a missing dataset, a wrong rank or row count, a string where numbers belong, NaN / Inf / huge values, time
// that stalls or runs backwards, declared sizes far beyond the data, odd attribute types). Mutating raw file images
// mostly exercises HDF5's parser and checksums; this reaches the readers' validation, which is ours.
#include <hdf5.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

namespace centaur_fuzz {

/// The image of a fuzz input: bytes after a first byte below 0x80 are a raw HDF5 file image (mutated real files);
/// after a first byte of 0x80 or above, the choices of build().
template <class Build>
std::string imageOf(const std::uint8_t* data, std::size_t size, Build build);

/// The fuzz input read as a stream of choices; zeros once exhausted.
class Choices {
 public:
  Choices(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  std::uint8_t byte() { return pos_ < size_ ? data_[pos_++] : 0; }
  unsigned below(unsigned n) { return n == 0 ? 0 : byte() % n; }
  bool oneIn(unsigned n) { return below(n) == 0; }
  /// A value for a slot that normally holds `normal`: usually `normal`, sometimes an extreme.
  double value(double normal) {
    if (!oneIn(24)) return normal;
    static const double special[] = {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                                     -std::numeric_limits<double>::infinity(), 1e308, -1e308, 0.0, -0.0, 1e-300,
                                     2.0, -1.0, 0.5, 1e9};
    return special[below(sizeof special / sizeof special[0])];
  }
  std::string text(std::size_t max) {
    std::string s;
    const std::size_t n = below(static_cast<unsigned>(max) + 1);
    for (std::size_t i = 0; i < n; ++i) s += static_cast<char>(byte());
    return s;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_, pos_ = 0;
};

/// Writes into an in-memory HDF5 file; image() returns its bytes.
class MemoryFile {
 public:
  MemoryFile() {
    const hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
    H5Pset_fapl_core(fapl, 1 << 16, 0);
    file_ = H5Fcreate("fuzz-image.h5", H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
    H5Pclose(fapl);
  }
  ~MemoryFile() {
    if (file_ >= 0) H5Fclose(file_);
  }
  hid_t root() const { return file_; }
  std::string image() {
    H5Fflush(file_, H5F_SCOPE_GLOBAL);
    const ssize_t n = H5Fget_file_image(file_, nullptr, 0);
    if (n <= 0) return {};
    std::string bytes(static_cast<std::size_t>(n), '\0');
    H5Fget_file_image(file_, bytes.data(), bytes.size());
    return bytes;
  }

 private:
  hid_t file_ = -1;
};

inline void stringAttribute(hid_t loc, const char* name, const std::string& value) {
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t a = H5Acreate2(loc, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
  const char* p = value.c_str();
  if (a >= 0) H5Awrite(a, type, &p), H5Aclose(a);
  H5Sclose(space), H5Tclose(type);
}

inline void stringListAttribute(hid_t loc, const char* name, const std::vector<std::string>& values) {
  std::vector<const char*> ptrs;
  for (const auto& v : values) ptrs.push_back(v.c_str());
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  const hsize_t n = values.size();
  const hid_t space = H5Screate_simple(1, &n, nullptr);
  const hid_t a = H5Acreate2(loc, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
  if (a >= 0 && n > 0) H5Awrite(a, type, ptrs.data());
  if (a >= 0) H5Aclose(a);
  H5Sclose(space), H5Tclose(type);
}

inline void numberAttribute(hid_t loc, const char* name, const std::vector<double>& values, bool scalar) {
  const hsize_t n = values.size();
  const hid_t space = scalar ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &n, nullptr);
  const hid_t a = H5Acreate2(loc, name, H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT);
  if (a >= 0 && !values.empty()) H5Awrite(a, H5T_NATIVE_DOUBLE, values.data());
  if (a >= 0) H5Aclose(a);
  H5Sclose(space);
}

/// A numeric attribute the format expects with `count` values near `normal`, or (by choice) another type or size.
inline void attribute(Choices& c, hid_t loc, const char* name, std::size_t count, double normal) {
  switch (c.below(12)) {
    case 0: return;  // missing
    case 1: stringAttribute(loc, name, c.text(8)); return;
    case 2: count = c.below(9); break;
    default: break;
  }
  std::vector<double> v(count);
  for (auto& x : v) x = c.value(normal);
  numberAttribute(loc, name, v, count == 1 && !c.oneIn(8));
}

/// Dataset `name` of `rows` rows of `trailing` extents; `fill(i)` gives the normal value of element i. By choice:
/// missing, a wrong rank or row count, strings, a huge declared shape never written, or corrupted values.
template <class Fill>
void dataset(Choices& c, hid_t loc, const char* name, hsize_t rows, std::vector<hsize_t> trailing, Fill fill) {
  std::vector<hsize_t> dims{rows};
  dims.insert(dims.end(), trailing.begin(), trailing.end());
  bool huge = false, strings = false;
  switch (c.below(20)) {
    case 0: return;
    case 1: dims.push_back(2); break;
    case 2:
      dims.pop_back();
      if (dims.empty()) dims.push_back(3);
      break;
    case 3: dims[0] = c.below(5); break;
    case 4: strings = true; break;
    case 5: huge = true; dims[0] = hsize_t{1} << (20 + c.below(24)); break;
    default: break;
  }
  const hid_t space = H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr);
  const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  if (huge) {
    std::vector<hsize_t> chunk(dims.size(), 1);
    chunk[0] = 1024;
    H5Pset_chunk(dcpl, static_cast<int>(chunk.size()), chunk.data());
  }
  const hid_t type = strings ? H5Tcopy(H5T_C_S1) : H5Tcopy(H5T_IEEE_F64LE);
  if (strings) H5Tset_size(type, 4);
  const hid_t ds = H5Dcreate2(loc, name, type, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  hsize_t total = 1;
  for (hsize_t d : dims) total *= d;
  if (ds >= 0 && !huge && total > 0 && total < (1u << 20)) {
    if (strings) {
      std::vector<char> text(total * 4, 'x');
      H5Dwrite(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, text.data());
    } else {
      std::vector<double> v(total);
      for (hsize_t i = 0; i < total; ++i) v[i] = c.value(fill(i));
      H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
    }
  }
  if (ds >= 0) H5Dclose(ds);
  H5Tclose(type), H5Pclose(dcpl), H5Sclose(space);
}

/// A sample period: usually 1 ms or 0.1 s, sometimes absurd.
inline double samplePeriod(Choices& c) {
  static const double dt[] = {0.001, 0.1, 0.001, 0.01, 1e-300, -0.001, 0.0, 1e3, 5e-5};
  return dt[c.below(sizeof dt / sizeof dt[0])];
}

inline std::string primitiveImage(Choices& c) {
  MemoryFile f;
  const char* formats[] = {"centaur-primitive", "centaur-primitive", "centaur-sim-log 1", "other"};
  if (!c.oneIn(6)) stringAttribute(f.root(), "format", formats[c.below(4)]);
  if (!c.oneIn(6)) numberAttribute(f.root(), "format_version", {c.value(1.0)}, true);
  const unsigned groups = 1 + c.below(2);
  for (unsigned g = 0; g < groups; ++g) {
    const std::string name = c.oneIn(4) ? c.text(6) : (g == 0 ? "squat-jump" : "half-squat-jump");
    const hid_t grp = H5Gcreate2(f.root(), name.empty() ? "g" : name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (grp < 0) continue;
    const hsize_t n = 2 + c.below(30);
    const double dt = samplePeriod(c);
    dataset(c, grp, "t", n, {}, [dt](hsize_t i) { return dt * static_cast<double>(i); });
    auto small = [](hsize_t i) { return 0.01 * static_cast<double>(i % 7); };
    for (auto [ds, cols] : {std::pair<const char*, hsize_t>{"q", 19}, {"nu", 18}, {"base_pos", 3}, {"base_vel", 3},
                            {"base_omega", 3}, {"tau", 12}}) {
      dataset(c, grp, ds, n, {cols}, small);
    }
    dataset(c, grp, "base_quat", n, {4}, [](hsize_t i) { return i % 4 == 0 ? 1.0 : 0.0; });
    for (const char* ds : {"foot_pos", "foot_pos_rel", "foot_vel_rel", "force"}) dataset(c, grp, ds, n, {4, 3}, small);
    dataset(c, grp, "contact", n, {4}, [](hsize_t i) { return static_cast<double>((i / 8) % 2); });
    const hid_t knots = c.oneIn(12) ? -1 : H5Gcreate2(grp, "knots", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (knots >= 0) {
      const hsize_t nk = c.oneIn(3) ? 0 : 2 + c.below(6);
      const double span = dt * static_cast<double>(n - 1), step = nk > 1 ? span / static_cast<double>(nk - 1) : 0.0;
      dataset(c, knots, "t", nk, {}, [step](hsize_t i) { return step * static_cast<double>(i); });
      dataset(c, knots, "x", nk, {37}, small);
      dataset(c, knots, "u", nk > 0 ? nk - 1 : 0, {31}, small);
      dataset(c, knots, "dt", nk > 0 ? nk - 1 : 0, {}, [step](hsize_t) { return step; });
      H5Gclose(knots);
    }
    if (!c.oneIn(8)) stringAttribute(grp, "solve_status", c.oneIn(3) ? c.text(12) : "solved");
    attribute(c, grp, "solve_iterations", 1, 42.0);
    attribute(c, grp, "solve_time_s", 1, 0.5);
    attribute(c, grp, "final_cost", 1, 10.0);
    attribute(c, grp, "total_mass", 1, 93.1);
    attribute(c, grp, "waist_com", 3, 0.1);
    if (c.oneIn(4)) stringAttribute(grp, "foot_order", c.oneIn(2) ? "FL,FR,RL,RR" : c.text(4));
    if (c.oneIn(6)) stringAttribute(grp, "kind", "arm-trajectory");
    H5Gclose(grp);
  }
  return f.image();
}

inline std::string armImage(Choices& c) {
  MemoryFile f;
  const hid_t grp = H5Gcreate2(f.root(), c.oneIn(8) ? "other" : "arm-flywheel", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  if (!c.oneIn(10)) stringAttribute(grp, "kind", c.oneIn(10) ? "primitive" : "arm-trajectory");
  if (!c.oneIn(10)) stringAttribute(grp, "joint_names", c.oneIn(6) ? "a,b" : "j1,j2,j3,j4,j5,j6,j7");
  const hsize_t n = 2 + c.below(30);
  const double period = c.oneIn(6) ? c.value(2.0) : 1.0, dt = period / static_cast<double>(n - 1);
  attribute(c, grp, "period", 1, period);
  dataset(c, grp, "t", n, {}, [dt](hsize_t i) { return dt * static_cast<double>(i); });
  for (auto [ds, cols] : {std::pair<const char*, hsize_t>{"q", 7}, {"qd", 7}, {"qdd", 7}, {"tau", 7}, {"h_ang", 3},
                          {"ee_pos", 3}}) {
    dataset(c, grp, ds, n, {cols}, [](hsize_t i) { return 0.1 * static_cast<double>(i % 5); });
  }
  if (!c.oneIn(3)) {
    const hid_t k = H5Gcreate2(grp, "knots", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    const hsize_t nk = 2 + c.below(5);
    dataset(c, k, "t", nk, {}, [&](hsize_t i) { return period * static_cast<double>(i) / static_cast<double>(nk - 1); });
    dataset(c, k, "x", nk, {14}, [](hsize_t) { return 0.0; });
    dataset(c, k, "u", nk - 1, {7}, [](hsize_t) { return 0.0; });
    H5Gclose(k);
  }
  for (auto [name, normal] : {std::pair<const char*, double>{"q_min", -1.0}, {"q_max", 1.0}, {"qd_max", 2.0},
                              {"tau_max", 5.0}, {"q_min_model", -2.0}, {"q_max_model", 2.0}, {"qd_max_model", 3.0},
                              {"tau_max_model", 6.0}}) {
    attribute(c, grp, name, 7, normal);
  }
  for (const char* name : {"momentum_point", "ee_box_min", "ee_box_max"}) attribute(c, grp, name, 3, 0.5);
  for (const char* name : {"solve_iterations", "solve_time_s", "solve_cost", "solve_max_violation"}) {
    attribute(c, grp, name, 1, 3.0);
  }
  for (const char* name : {"ee_frame", "solve_status", "config_yaml"}) {
    if (!c.oneIn(10)) stringAttribute(grp, name, c.oneIn(4) ? c.text(10) : "solved");
  }
  H5Gclose(grp);
  return f.image();
}

inline std::string simLogImage(Choices& c) {
  MemoryFile f;
  const hid_t root = f.root();
  if (!c.oneIn(10)) stringAttribute(root, "format", c.oneIn(8) ? "centaur-primitive" : "centaur-sim-log 1");
  const unsigned joints = c.below(5), bodies = c.below(3);
  std::vector<std::string> jn, bn;
  for (unsigned i = 0; i < joints; ++i) jn.push_back("j" + std::to_string(i));
  for (unsigned i = 0; i < bodies; ++i) bn.push_back("w" + std::to_string(i));
  if (!c.oneIn(10)) stringListAttribute(root, "joint_names", jn);
  if (!c.oneIn(10)) stringListAttribute(root, "contact_bodies", bn);
  for (const char* name : {"config", "scenario"}) {
    if (!c.oneIn(10)) stringAttribute(root, name, c.text(8));
  }
  const hsize_t n = c.below(20);
  const double dt = samplePeriod(c);
  dataset(c, root, "t", n, {}, [dt](hsize_t i) { return dt * static_cast<double>(i); });
  auto zero = [](hsize_t) { return 0.0; };
  for (const char* ds : {"q", "qd", "tau_cmd", "tau_meas", "tau_applied", "q_ref", "qd_ref", "tau_ff", "kp", "kd"}) {
    dataset(c, root, ds, n, {joints}, zero);
  }
  auto quat = [](hsize_t i) { return i % 4 == 0 ? 1.0 : 0.0; };
  dataset(c, root, "imu_quat", n, {4}, quat);
  dataset(c, root, "base_quat", n, {4}, quat);
  for (const char* ds : {"imu_omega", "imu_acc", "base_pos"}) dataset(c, root, ds, n, {3}, zero);
  dataset(c, root, "base_vel", n, {6}, zero);
  dataset(c, root, "wheel_force", n, {bodies, 3}, zero);
  return f.image();
}

template <class Build>
std::string imageOf(const std::uint8_t* data, std::size_t size, Build build) {
  // HDF5's own error printing off; its free lists unbounded, so that the ~0.5 MB metadata cache of every file
  // opened is reused instead of being mapped, zeroed and unmapped by the sanitizer's allocator per input (3x faster).
  static const bool ready = [] {
    return H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr) >= 0 && H5set_free_list_limits(-1, -1, -1, -1, -1, -1) >= 0;
  }();
  (void)ready;
  if (size == 0) return {};
  if (data[0] < 0x80) return std::string(reinterpret_cast<const char*>(data + 1), size - 1);
  Choices c(data + 1, size - 1);
  return build(c);
}

}  // namespace centaur_fuzz
