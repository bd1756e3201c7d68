#include "planner/primitive_io.hpp"

#include <hdf5.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <set>
#include <sstream>
#include <utility>

#include "common/atomic_file.hpp"
#include "common/error.hpp"

namespace centaur::planner {
namespace {

constexpr hsize_t kNq = 19;     // template q: p(3), quat w,x,y,z (4), q_C (12)
constexpr hsize_t kNv = 18;     // template nu: v(3), omega(3), qdot_C (12)
constexpr hsize_t kFeet = 4;
constexpr hsize_t kJoints = 12;
constexpr hsize_t kChunkRows = 1024;
constexpr unsigned kMaxCompactAttributes = 4096;

// Group attributes the library owns; Primitive::scalars/vectors/strings may not use these names.
const std::set<std::string>& reservedAttributes() {
  static const std::set<std::string> names = {
      "solve_status", "solve_iterations", "solve_time_s", "final_cost", "max_constraint_violation",
      "config_yaml",  "foot_order",       "quaternion_order", "units",  "force_convention",
      "frames",       "format",           "format_version"};
  return names;
}

void silenceHdf5() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

herr_t innermostError(unsigned n, const H5E_error2_t* err, void* data) {
  if (n == 0 && err != nullptr && err->desc != nullptr) *static_cast<std::string*>(data) = err->desc;
  return 0;
}

/// The most specific message on HDF5's error stack ("" if none).
std::string hdf5Message() {
  std::string msg;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, innermostError, &msg);
  return msg.empty() ? std::string() : " (HDF5: " + msg + ")";
}

/// Owns an HDF5 identifier and closes it with the matching H5?close.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& o) noexcept : id_(std::exchange(o.id_, -1)), closer_(o.closer_) {}
  Handle& operator=(Handle&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = std::exchange(o.id_, -1);
      closer_ = o.closer_;
    }
    return *this;
  }
  ~Handle() { reset(); }
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  /// Close now and report whether closing succeeded (a file flushes on close).
  bool close() {
    const herr_t rc = id_ >= 0 && closer_ != nullptr ? closer_(id_) : 0;
    id_ = -1;
    return rc >= 0;
  }
  void reset() {
    if (id_ >= 0 && closer_ != nullptr) closer_(id_);
    id_ = -1;
  }

 private:
  hid_t id_ = -1;
  Closer closer_ = nullptr;
};

std::string shapeText(const std::vector<hsize_t>& dims) {
  std::ostringstream s;
  s << "(";
  for (std::size_t i = 0; i < dims.size(); ++i) s << (i ? ", " : "") << dims[i];
  s << ")";
  return s.str();
}

// =====================================================================================================
// Writing
// =====================================================================================================

struct Meta {
  const char* units;        ///< "units" attribute
  const char* frame;        ///< "frame" attribute, nullptr if not applicable
  const char* description;  ///< "description" attribute
};

class Writer {
 public:
  explicit Writer(std::string target) : target_(std::move(target)) {}

  [[noreturn]] void fail(const std::string& what) const {
    throw RuntimeError("cannot write " + target_ + ": " + what + hdf5Message());
  }
  hid_t check(hid_t id, const std::string& what) const {
    if (id < 0) fail(what);
    return id;
  }
  void ok(herr_t rc, const std::string& what) const {
    if (rc < 0) fail(what);
  }

  void stringAttribute(hid_t loc, const std::string& name, const std::string& value) const {
    Handle type(check(H5Tcopy(H5T_C_S1), "string type"), H5Tclose);
    ok(H5Tset_size(type.get(), H5T_VARIABLE), "string type");
    ok(H5Tset_cset(type.get(), H5T_CSET_UTF8), "string type");
    Handle space(check(H5Screate(H5S_SCALAR), "dataspace"), H5Sclose);
    Handle attr(check(H5Acreate2(loc, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
                      "attribute '" + name + "'"),
                H5Aclose);
    const char* data = value.c_str();
    ok(H5Awrite(attr.get(), type.get(), &data), "attribute '" + name + "'");
  }

  void doubleAttribute(hid_t loc, const std::string& name, double value) const {
    Handle space(check(H5Screate(H5S_SCALAR), "dataspace"), H5Sclose);
    Handle attr(check(H5Acreate2(loc, name.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                      "attribute '" + name + "'"),
                H5Aclose);
    ok(H5Awrite(attr.get(), H5T_NATIVE_DOUBLE, &value), "attribute '" + name + "'");
  }

  void intAttribute(hid_t loc, const std::string& name, int value) const {
    Handle space(check(H5Screate(H5S_SCALAR), "dataspace"), H5Sclose);
    Handle attr(check(H5Acreate2(loc, name.c_str(), H5T_STD_I32LE, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                      "attribute '" + name + "'"),
                H5Aclose);
    ok(H5Awrite(attr.get(), H5T_NATIVE_INT, &value), "attribute '" + name + "'");
  }

  void vectorAttribute(hid_t loc, const std::string& name, const std::vector<double>& value) const {
    const hsize_t n = value.size();
    Handle space(check(H5Screate_simple(1, &n, nullptr), "dataspace"), H5Sclose);
    Handle attr(check(H5Acreate2(loc, name.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                      "attribute '" + name + "'"),
                H5Aclose);
    if (n > 0) ok(H5Awrite(attr.get(), H5T_NATIVE_DOUBLE, value.data()), "attribute '" + name + "'");
  }

  /// A dataset of `dims` from contiguous row-major memory `data` (memory type `mem_type`).
  void dataset(hid_t loc, const std::string& name, const std::vector<hsize_t>& dims, hid_t file_type,
               hid_t mem_type, const void* data, const Meta& meta) const {
    Handle space(check(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), "dataspace"),
                 H5Sclose);
    hsize_t total = 1;
    for (hsize_t d : dims) total *= d;
    Handle dcpl(check(H5Pcreate(H5P_DATASET_CREATE), "property list"), H5Pclose);
    if (total > 0 && H5Zfilter_avail(H5Z_FILTER_DEFLATE) > 0) {
      std::vector<hsize_t> chunk = dims;
      chunk[0] = std::min<hsize_t>(dims[0], kChunkRows);
      ok(H5Pset_chunk(dcpl.get(), static_cast<int>(chunk.size()), chunk.data()), "chunking");
      ok(H5Pset_shuffle(dcpl.get()), "shuffle filter");
      ok(H5Pset_deflate(dcpl.get(), 4), "deflate filter");
    }
    Handle ds(check(H5Dcreate2(loc, name.c_str(), file_type, space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT),
                    "dataset '" + name + "'"),
              H5Dclose);
    if (total > 0) {
      ok(H5Dwrite(ds.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "dataset '" + name + "'");
    }
    stringAttribute(ds.get(), "units", meta.units);
    if (meta.frame != nullptr) stringAttribute(ds.get(), "frame", meta.frame);
    stringAttribute(ds.get(), "description", meta.description);
  }

 private:
  std::string target_;
};

/// Rows must equal `rows` and columns `cols` (cols 0 = any); otherwise the primitive is inconsistent.
void requireShape(const Writer& w, const Primitive& p, const char* field, Eigen::Index rows, Eigen::Index cols,
                  Eigen::Index want_rows, Eigen::Index want_cols) {
  if (rows != want_rows || (want_cols > 0 && cols != want_cols)) {
    std::ostringstream s;
    s << "primitive '" << p.name << "': " << field << " is " << rows << " x " << cols << ", expected "
      << want_rows << " x " << (want_cols > 0 ? std::to_string(want_cols) : std::string("any"));
    w.fail(s.str());
  }
}

void writeMatrix(const Writer& w, hid_t loc, const Primitive& p, const std::string& name, const RowMatrix& m,
                 Eigen::Index rows, const std::vector<hsize_t>& trailing, const Meta& meta) {
  Eigen::Index cols = 1;
  for (hsize_t d : trailing) cols *= static_cast<Eigen::Index>(d);
  requireShape(w, p, name.c_str(), m.rows(), m.cols(), rows, cols);
  std::vector<hsize_t> dims{static_cast<hsize_t>(rows)};
  dims.insert(dims.end(), trailing.begin(), trailing.end());
  w.dataset(loc, name, dims, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, m.data(), meta);
}

void writeVector(const Writer& w, hid_t loc, const Primitive& p, const std::string& name, const Eigen::VectorXd& v,
                 Eigen::Index rows, const Meta& meta) {
  requireShape(w, p, name.c_str(), v.size(), 1, rows, 1);
  w.dataset(loc, name, {static_cast<hsize_t>(rows)}, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, v.data(), meta);
}

void writeGroup(const Writer& w, hid_t file, const Primitive& p) {
  // Keep the group's attributes in compact storage (in the object header). HDF5 1.10 crashes in H5Ocopy
  // (h5copy, h5py's Group.copy) on variable-length string attributes held in dense storage, which the
  // library would otherwise switch to beyond 8 attributes. Strings live in the global heap, so compact
  // storage has no practical size limit for them.
  Handle gcpl(w.check(H5Pcreate(H5P_GROUP_CREATE), "property list"), H5Pclose);
  w.ok(H5Pset_attr_phase_change(gcpl.get(), kMaxCompactAttributes, 0), "attribute storage");
  Handle g(w.check(H5Gcreate2(file, p.name.c_str(), H5P_DEFAULT, gcpl.get(), H5P_DEFAULT),
                   "group '" + p.name + "'"),
           H5Gclose);
  const hid_t gid = g.get();
  const Eigen::Index n = p.t.size();
  const std::vector<hsize_t> foot3{kFeet, 3};

  writeVector(w, gid, p, "t", p.t, n, {"s", nullptr, "sample times at 1 kHz, starting at 0"});
  writeMatrix(w, gid, p, "q", p.q, n, {kNq},
              {"m, quaternion (unitless), m", "W (base), B (legs)",
               "template generalized coordinates [p_W(3), quat w,x,y,z (4), q_C (12): foot positions in B, "
               "foot-major FL,FR,RL,RR x,y,z]"});
  writeMatrix(w, gid, p, "nu", p.nu, n, {kNv},
              {"m/s, rad/s, m/s", "W (v, omega), B (qdot_C)",
               "template generalized velocities [v_W(3), omega_W(3), qdot_C(12)]"});
  writeMatrix(w, gid, p, "base_pos", p.base_pos, n, {3}, {"m", "W", "waist origin position"});
  writeMatrix(w, gid, p, "base_quat", p.base_quat, n, {4},
              {"1", "W_R_B", "waist orientation, unit quaternion (see attribute order)"});
  writeMatrix(w, gid, p, "base_vel", p.base_vel, n, {3}, {"m/s", "W", "waist origin linear velocity"});
  writeMatrix(w, gid, p, "base_omega", p.base_omega, n, {3}, {"rad/s", "W", "waist angular velocity"});
  writeMatrix(w, gid, p, "foot_pos", p.foot_pos, n, foot3,
              {"m", "W", "foot points (wheel centres), [sample, foot FL,FR,RL,RR, xyz]"});
  writeMatrix(w, gid, p, "foot_pos_rel", p.foot_pos_rel, n, foot3,
              {"m", "B", "foot points relative to the waist origin, in the waist frame (r_C)"});
  writeMatrix(w, gid, p, "foot_vel_rel", p.foot_vel_rel, n, foot3,
              {"m/s", "B", "time derivative of foot_pos_rel, in the waist frame"});
  writeMatrix(w, gid, p, "force", p.force, n, foot3,
              {"N", "W", "contact force exerted by the environment on the robot at each foot"});

  // contact: uint8 0/1
  requireShape(w, p, "contact", p.contact.rows(), p.contact.cols(), n, static_cast<Eigen::Index>(kFeet));
  std::vector<std::uint8_t> contact(static_cast<std::size_t>(p.contact.size()));
  for (Eigen::Index i = 0; i < p.contact.size(); ++i) {
    const double c = p.contact.data()[i];
    if (c != 0.0 && c != 1.0) {
      w.fail("primitive '" + p.name + "': contact holds " + std::to_string(c) + ", allowed values are 0 and 1");
    }
    contact[static_cast<std::size_t>(i)] = c == 1.0 ? 1 : 0;
  }
  w.dataset(gid, "contact", {static_cast<hsize_t>(n), kFeet}, H5T_STD_U8LE, H5T_NATIVE_UINT8, contact.data(),
            {"1", nullptr, "planned contact, 1 = in contact, per foot FL,FR,RL,RR"});
  writeMatrix(w, gid, p, "tau", p.tau, n, {kJoints},
              {"N", "B", "prismatic leg joint forces of the template (actuated rows of eq. 4), FL,FR,RL,RR x,y,z"});

  // base_quat order attribute
  {
    Handle ds(w.check(H5Dopen2(gid, "base_quat", H5P_DEFAULT), "dataset 'base_quat'"), H5Dclose);
    w.stringAttribute(ds.get(), "order", "w,x,y,z");
  }

  // knots
  {
    Handle k(w.check(H5Gcreate2(gid, "knots", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), "group 'knots'"), H5Gclose);
    const Eigen::Index nk = p.knot_t.size();
    const Eigen::Index ns = nk > 0 ? nk - 1 : 0;
    writeVector(w, k.get(), p, "t", p.knot_t, nk, {"s", nullptr, "node times t_k (N_s + 1)"});
    writeMatrix(w, k.get(), p, "x", p.knot_x, nk, {static_cast<hsize_t>(p.knot_x.cols())},
                {"SI", "see q, nu", "OCP states x_k = [q_k, nu_k] at the nodes"});
    writeMatrix(w, k.get(), p, "u", p.knot_u, ns, {static_cast<hsize_t>(p.knot_u.cols())},
                {"SI", "W (nu_dot base, forces), B (qddot_C)",
                 "OCP controls u_k, piecewise constant over each interval"});
    writeVector(w, k.get(), p, "dt", p.knot_dt, ns, {"s", nullptr, "interval durations dt_k (N_s)"});
  }

  // metadata
  std::set<std::string> keys;
  auto claim = [&](const std::string& key) {
    if (key.empty() || reservedAttributes().count(key) > 0 || !keys.insert(key).second) {
      w.fail("primitive '" + p.name + "': metadata key '" + key +
             "' is empty, reserved or used twice (scalars, vectors and strings share one namespace)");
    }
  };
  for (const auto& [key, value] : p.scalars) {
    claim(key);
    w.doubleAttribute(gid, key, value);
  }
  for (const auto& [key, value] : p.vectors) {
    claim(key);
    w.vectorAttribute(gid, key, value);
  }
  for (const auto& [key, value] : p.strings) {
    claim(key);
    w.stringAttribute(gid, key, value);
  }
  w.stringAttribute(gid, "solve_status", p.solve.status);
  w.intAttribute(gid, "solve_iterations", p.solve.iterations);
  w.doubleAttribute(gid, "solve_time_s", p.solve.solve_time_s);
  w.doubleAttribute(gid, "final_cost", p.solve.cost);
  w.doubleAttribute(gid, "max_constraint_violation", p.solve.max_constraint_violation);
  w.stringAttribute(gid, "config_yaml", p.config_yaml);
  w.stringAttribute(gid, "foot_order", "FL,FR,RL,RR");
  w.stringAttribute(gid, "quaternion_order", "w,x,y,z");
  w.stringAttribute(gid, "units", "SI: s, m, kg, N, rad; each dataset states its units in attribute 'units'");
  w.stringAttribute(gid, "force_convention",
                    "force = force exerted by the environment on the robot at the foot, world frame W");
  w.stringAttribute(gid, "frames",
                    "W = world (z up, gravity -z); B = waist (base) frame; feet = wheel centres FL,FR,RL,RR "
                    "= wheel_1..wheel_4");
}

void checkName(const std::string& target, const std::string& name) {
  if (name.empty() || name == "." || name.find('/') != std::string::npos) {
    throw RuntimeError("cannot write " + target + ": primitive name '" + name +
                       "' is not a valid HDF5 group name (non-empty, no '/')");
  }
}

void writeFile(const std::string& tmp, const std::string& target, const std::vector<const Primitive*>& prims) {
  const Writer w(target);
  Handle fcpl(w.check(H5Pcreate(H5P_FILE_CREATE), "property list"), H5Pclose);
  w.ok(H5Pset_link_creation_order(fcpl.get(), H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED), "creation order");
  Handle fapl(w.check(H5Pcreate(H5P_FILE_ACCESS), "property list"), H5Pclose);
  // The 1.8 format: readable by HDF5 >= 1.8 (h5py, MATLAB) and stores large attributes (config_yaml) densely.
  w.ok(H5Pset_libver_bounds(fapl.get(), H5F_LIBVER_V18, H5F_LIBVER_V18), "format version");
  Handle file(w.check(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, fcpl.get(), fapl.get()), "cannot create " + tmp),
              H5Fclose);
  w.stringAttribute(file.get(), "format", "centaur-primitive");
  w.intAttribute(file.get(), "format_version", kPrimitiveFormatVersion);
  w.stringAttribute(file.get(), "description",
                    "lower-body primitives planned offline by centaur; one group per primitive; "
                    "schema in docs/primitive-format.md");
  for (const Primitive* p : prims) writeGroup(w, file.get(), *p);
  if (!file.close()) w.fail("closing (flushing) the file failed");
}

// =====================================================================================================
// Reading
// =====================================================================================================

class Reader {
 public:
  explicit Reader(std::string path) : path_(std::move(path)) {
    silenceHdf5();
    std::error_code ec;
    if (!std::filesystem::exists(path_, ec)) {
      throw InputError(path_ + ": no such file (expected an HDF5 primitive file written by `centaur plan`)");
    }
    if (std::filesystem::is_directory(path_, ec)) throw InputError(path_ + ": is a directory, not an HDF5 file");
    file_ = Handle(H5Fopen(path_.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
    if (!file_.valid()) {
      throw InputError(path_ + ": not an HDF5 file or corrupt, cannot open it" + hdf5Message());
    }
  }

  hid_t file() const { return file_.get(); }
  const std::string& path() const { return path_; }

  [[noreturn]] void fail(const std::string& key, const std::string& message) const {
    throw InputError(path_, key, message);
  }

  std::vector<std::string> groupNames() const {
    std::vector<std::string> names;
    hsize_t idx = 0;
    herr_t rc = H5Literate(file(), H5_INDEX_CRT_ORDER, H5_ITER_INC, &idx, collectGroup, &names);
    if (rc < 0) {  // files written without a creation-order index (e.g. by other tools): alphabetical
      names.clear();
      idx = 0;
      rc = H5Literate(file(), H5_INDEX_NAME, H5_ITER_INC, &idx, collectGroup, &names);
    }
    if (rc < 0) throw InputError(path_ + ": cannot list the groups (corrupt file?)" + hdf5Message());
    // Other kinds of groups may share the file (e.g. an arm-flywheel trajectory, attribute kind =
    // "arm-trajectory"): lower-body primitives have no `kind` attribute.
    std::vector<std::string> primitives;
    for (const std::string& n : names) {
      Handle gid(H5Gopen2(file(), n.c_str(), H5P_DEFAULT), H5Gclose);
      if (gid.valid() && H5Aexists(gid.get(), "kind") > 0) continue;
      primitives.push_back(n);
    }
    return primitives;
  }

  /// Dataset `name` in `loc` as doubles (row-major). `want` gives the expected shape; 0 = any extent.
  std::vector<double> doubles(hid_t loc, const std::string& key, const std::string& name,
                              const std::vector<hsize_t>& want, std::vector<hsize_t>& dims) const {
    if (H5Lexists(loc, name.c_str(), H5P_DEFAULT) <= 0) fail(key, "missing dataset");
    Handle ds(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), H5Dclose);
    if (!ds.valid()) fail(key, "cannot open dataset (not a dataset, or corrupt)" + hdf5Message());
    Handle space(H5Dget_space(ds.get()), H5Sclose);
    const int rank = space.valid() ? H5Sget_simple_extent_ndims(space.get()) : -1;
    if (rank < 0) fail(key, "cannot read the dataspace (corrupt?)" + hdf5Message());
    dims.assign(static_cast<std::size_t>(rank), 0);
    if (rank > 0) H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
    bool ok = dims.size() == want.size();
    for (std::size_t i = 0; ok && i < want.size(); ++i) ok = want[i] == 0 || want[i] == dims[i];
    if (!ok) {
      std::ostringstream s;
      s << "dataset has shape " << shapeText(dims) << ", expected (";
      for (std::size_t i = 0; i < want.size(); ++i) {
        s << (i ? ", " : "") << (want[i] == 0 ? std::string(i == 0 ? "N" : "any") : std::to_string(want[i]));
      }
      s << ")";
      fail(key, s.str());
    }
    Handle type(H5Dget_type(ds.get()), H5Tclose);
    const H5T_class_t cls = type.valid() ? H5Tget_class(type.get()) : H5T_NO_CLASS;
    if (cls != H5T_FLOAT && cls != H5T_INTEGER) fail(key, "dataset is not numeric");
    hsize_t total = 1;
    for (hsize_t d : dims) total *= d;
    std::vector<double> out(static_cast<std::size_t>(total));
    if (total > 0 && H5Dread(ds.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0) {
      fail(key, "cannot read dataset (corrupt?)" + hdf5Message());
    }
    return out;
  }

  RowMatrix matrix(hid_t loc, const std::string& key, const std::string& name, std::vector<hsize_t> want) const {
    std::vector<hsize_t> dims;
    const std::vector<double> data = doubles(loc, key, name, want, dims);
    const auto rows = static_cast<Eigen::Index>(dims.empty() ? 1 : dims[0]);
    Eigen::Index cols = 1;
    for (std::size_t i = 1; i < dims.size(); ++i) cols *= static_cast<Eigen::Index>(dims[i]);
    RowMatrix m(rows, cols);
    if (!data.empty()) std::copy(data.begin(), data.end(), m.data());
    return m;
  }

  Eigen::VectorXd vector(hid_t loc, const std::string& key, const std::string& name, hsize_t want) const {
    std::vector<hsize_t> dims;
    const std::vector<double> data = doubles(loc, key, name, {want}, dims);
    Eigen::VectorXd v(static_cast<Eigen::Index>(data.size()));
    if (!data.empty()) std::copy(data.begin(), data.end(), v.data());
    return v;
  }

 private:
  static herr_t collectGroup(hid_t loc, const char* name, const H5L_info_t* /*info*/, void* data) {
    Handle obj(H5Oopen(loc, name, H5P_DEFAULT), H5Oclose);
    if (obj.valid() && H5Iget_type(obj.get()) == H5I_GROUP) {
      static_cast<std::vector<std::string>*>(data)->emplace_back(name);
    }
    return 0;
  }

  std::string path_;
  Handle file_;
};

/// What one attribute holds, once read.
struct AttributeValue {
  enum Kind { kString, kScalar, kVector, kUnsupported } kind = kUnsupported;
  std::string text;
  std::vector<double> numbers;
};

AttributeValue readAttribute(hid_t attr) {
  AttributeValue v;
  Handle type(H5Aget_type(attr), H5Tclose);
  Handle space(H5Aget_space(attr), H5Sclose);
  if (!type.valid() || !space.valid()) return v;
  const H5S_class_t sclass = H5Sget_simple_extent_type(space.get());
  const H5T_class_t tclass = H5Tget_class(type.get());
  if (tclass == H5T_STRING) {
    if (sclass != H5S_SCALAR) return v;
    if (H5Tis_variable_str(type.get()) > 0) {
      Handle mem(H5Tcopy(H5T_C_S1), H5Tclose);
      H5Tset_size(mem.get(), H5T_VARIABLE);
      H5Tset_cset(mem.get(), H5Tget_cset(type.get()));
      char* buf = nullptr;
      if (H5Aread(attr, mem.get(), &buf) < 0) return v;
      v.text = buf != nullptr ? std::string(buf) : std::string();
      H5free_memory(buf);
    } else {
      const std::size_t size = H5Tget_size(type.get());
      std::vector<char> buf(size + 1, '\0');
      if (H5Aread(attr, type.get(), buf.data()) < 0) return v;
      v.text.assign(buf.data(), strnlen(buf.data(), size));
    }
    v.kind = AttributeValue::kString;
    return v;
  }
  if (tclass != H5T_FLOAT && tclass != H5T_INTEGER) return v;
  if (sclass == H5S_SCALAR) {
    double x = 0.0;
    if (H5Aread(attr, H5T_NATIVE_DOUBLE, &x) < 0) return v;
    v.kind = AttributeValue::kScalar;
    v.numbers = {x};
    return v;
  }
  if (sclass == H5S_SIMPLE || sclass == H5S_NULL) {
    const hssize_t n = sclass == H5S_NULL ? 0 : H5Sget_simple_extent_npoints(space.get());
    if (n < 0 || (sclass == H5S_SIMPLE && H5Sget_simple_extent_ndims(space.get()) != 1)) return v;
    v.numbers.resize(static_cast<std::size_t>(n));
    if (n > 0 && H5Aread(attr, H5T_NATIVE_DOUBLE, v.numbers.data()) < 0) return v;
    v.kind = AttributeValue::kVector;
  }
  return v;
}

struct AttributeSink {
  Primitive* prim;
  std::vector<std::string> bad;  // reserved attributes of the wrong type
};

herr_t collectAttribute(hid_t loc, const char* name, const H5A_info_t* /*info*/, void* data) {
  auto* sink = static_cast<AttributeSink*>(data);
  Primitive& p = *sink->prim;
  Handle attr(H5Aopen(loc, name, H5P_DEFAULT), H5Aclose);
  if (!attr.valid()) return 0;
  const AttributeValue v = readAttribute(attr.get());
  const std::string key(name);
  const bool is_string = v.kind == AttributeValue::kString;
  const bool is_scalar = v.kind == AttributeValue::kScalar;
  auto expect = [&](bool ok) {
    if (!ok) sink->bad.push_back(key);
    return ok;
  };
  if (key == "solve_status") {
    if (expect(is_string)) p.solve.status = v.text;
  } else if (key == "solve_iterations") {
    if (expect(is_scalar)) p.solve.iterations = static_cast<int>(std::lround(v.numbers[0]));
  } else if (key == "solve_time_s") {
    if (expect(is_scalar)) p.solve.solve_time_s = v.numbers[0];
  } else if (key == "final_cost") {
    if (expect(is_scalar)) p.solve.cost = v.numbers[0];
  } else if (key == "max_constraint_violation") {
    if (expect(is_scalar)) p.solve.max_constraint_violation = v.numbers[0];
  } else if (key == "config_yaml") {
    if (expect(is_string)) p.config_yaml = v.text;
  } else if (key == "foot_order") {
    if (expect(is_string) && v.text != "FL,FR,RL,RR") sink->bad.push_back(key + " (must be FL,FR,RL,RR)");
  } else if (key == "quaternion_order") {
    if (expect(is_string) && v.text != "w,x,y,z") sink->bad.push_back(key + " (must be w,x,y,z)");
  } else if (reservedAttributes().count(key) > 0) {
    // descriptive notes written by the library
  } else if (is_string) {
    p.strings[key] = v.text;
  } else if (is_scalar) {
    p.scalars[key] = v.numbers[0];
  } else if (v.kind == AttributeValue::kVector) {
    p.vectors[key] = v.numbers;
  }  // other attribute kinds (string arrays, matrices, compounds) are not part of the schema: ignored
  return 0;
}

Primitive readGroup(const Reader& r, const std::string& name) {
  Handle g(H5Gopen2(r.file(), name.c_str(), H5P_DEFAULT), H5Gclose);
  if (!g.valid()) r.fail(name, "cannot open group (corrupt?)" + hdf5Message());
  const hid_t gid = g.get();
  Primitive p;
  p.name = name;
  const std::string k = name + "/";
  p.t = r.vector(gid, k + "t", "t", 0);
  const auto n = static_cast<hsize_t>(p.t.size());
  p.q = r.matrix(gid, k + "q", "q", {n, kNq});
  p.nu = r.matrix(gid, k + "nu", "nu", {n, kNv});
  p.base_pos = r.matrix(gid, k + "base_pos", "base_pos", {n, 3});
  p.base_quat = r.matrix(gid, k + "base_quat", "base_quat", {n, 4});
  p.base_vel = r.matrix(gid, k + "base_vel", "base_vel", {n, 3});
  p.base_omega = r.matrix(gid, k + "base_omega", "base_omega", {n, 3});
  p.foot_pos = r.matrix(gid, k + "foot_pos", "foot_pos", {n, kFeet, 3});
  p.foot_pos_rel = r.matrix(gid, k + "foot_pos_rel", "foot_pos_rel", {n, kFeet, 3});
  p.foot_vel_rel = r.matrix(gid, k + "foot_vel_rel", "foot_vel_rel", {n, kFeet, 3});
  p.force = r.matrix(gid, k + "force", "force", {n, kFeet, 3});
  p.contact = r.matrix(gid, k + "contact", "contact", {n, kFeet});
  for (Eigen::Index i = 0; i < p.contact.size(); ++i) {
    const double c = p.contact.data()[i];
    if (c != 0.0 && c != 1.0) r.fail(k + "contact", "holds " + std::to_string(c) + ", allowed values are 0 and 1");
  }
  p.tau = r.matrix(gid, k + "tau", "tau", {n, kJoints});

  if (H5Lexists(gid, "knots", H5P_DEFAULT) <= 0) r.fail(k + "knots", "missing group");
  Handle knots(H5Gopen2(gid, "knots", H5P_DEFAULT), H5Gclose);
  if (!knots.valid()) r.fail(k + "knots", "cannot open group (corrupt?)" + hdf5Message());
  const std::string kk = k + "knots/";
  p.knot_t = r.vector(knots.get(), kk + "t", "t", 0);
  const auto nk = static_cast<hsize_t>(p.knot_t.size());
  const hsize_t ns = nk > 0 ? nk - 1 : 0;
  p.knot_x = r.matrix(knots.get(), kk + "x", "x", {nk, 0});
  p.knot_u = r.matrix(knots.get(), kk + "u", "u", {ns, 0});
  p.knot_dt = r.vector(knots.get(), kk + "dt", "dt", ns);

  AttributeSink sink{&p, {}};
  hsize_t idx = 0;
  if (H5Aiterate2(gid, H5_INDEX_NAME, H5_ITER_INC, &idx, collectAttribute, &sink) < 0) {
    r.fail(name, "cannot read the group attributes (corrupt?)" + hdf5Message());
  }
  if (!sink.bad.empty()) r.fail(k + sink.bad.front(), "attribute has the wrong type or value");
  return p;
}

}  // namespace

// =====================================================================================================
// Public API
// =====================================================================================================

void writePrimitives(const std::string& path, const std::vector<Primitive>& prims, WriteMode mode) {
  silenceHdf5();
  std::set<std::string> seen;
  for (const Primitive& p : prims) {
    checkName(path, p.name);
    if (!seen.insert(p.name).second) {
      throw RuntimeError("cannot write " + path + ": primitive name '" + p.name + "' appears twice");
    }
  }
  // Append = rewrite the whole file: existing groups (in their order, replaced in place by a new primitive
  // of the same name), then the new ones. The file stays compact and the target is only ever replaced whole.
  std::vector<Primitive> existing;
  std::error_code ec;
  if (mode == WriteMode::Append && std::filesystem::exists(path, ec)) existing = readPrimitives(path);
  std::vector<const Primitive*> order;
  for (const Primitive& e : existing) {
    const auto it = std::find_if(prims.begin(), prims.end(), [&](const Primitive& p) { return p.name == e.name; });
    order.push_back(it != prims.end() ? &*it : &e);
  }
  for (const Primitive& p : prims) {
    if (std::none_of(existing.begin(), existing.end(), [&](const Primitive& e) { return e.name == p.name; })) {
      order.push_back(&p);
    }
  }
  ensureParentDirectory(path);
  const std::string tmp = temporaryPathFor(path);
  try {
    writeFile(tmp, path, order);
  } catch (...) {
    removeFileIfExists(tmp);
    throw;
  }
  commitFile(tmp, path);
}

void writePrimitive(const std::string& path, const Primitive& prim, WriteMode mode) {
  writePrimitives(path, std::vector<Primitive>{prim}, mode);
}

std::vector<std::string> listPrimitives(const std::string& path) {
  const Reader r(path);
  return r.groupNames();
}

std::vector<Primitive> readPrimitives(const std::string& path) {
  const Reader r(path);
  std::vector<Primitive> out;
  for (const std::string& name : r.groupNames()) out.push_back(readGroup(r, name));
  return out;
}

Primitive readPrimitive(const std::string& path, const std::string& name) {
  const Reader r(path);
  const std::vector<std::string> names = r.groupNames();
  if (std::find(names.begin(), names.end(), name) == names.end()) {
    std::string available;
    for (const std::string& n : names) available += (available.empty() ? "" : ", ") + n;
    r.fail(name, "no such primitive; the file holds: " + (available.empty() ? std::string("none") : available));
  }
  return readGroup(r, name);
}

}  // namespace centaur::planner
