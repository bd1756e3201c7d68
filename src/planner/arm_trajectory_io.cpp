// HDF5 I/O of the arm-flywheel trajectory (C API; see arm_trajectory_io.hpp and docs/primitive-format.md).
#include "planner/arm_trajectory_io.hpp"

#include <hdf5.h>

#include <cstring>
#include <filesystem>
#include <sstream>
#include <utility>
#include <vector>

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "planner/primitive_io.hpp"

namespace centaur::planner {

namespace {

class H {  // owns an HDF5 id
 public:
  using Closer = herr_t (*)(hid_t);
  H(hid_t id, Closer c) : id_(id), c_(c) {}
  H(const H&) = delete;
  H& operator=(const H&) = delete;
  ~H() {
    if (id_ >= 0) c_(id_);
  }
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  bool close() {
    const herr_t rc = id_ >= 0 ? c_(id_) : 0;
    id_ = -1;
    return rc >= 0;
  }

 private:
  hid_t id_;
  Closer c_;
};

struct W {
  std::string target;
  [[noreturn]] void fail(const std::string& what) const { throw RuntimeError("cannot write " + target + ": " + what); }
  hid_t check(hid_t id, const std::string& what) const {
    if (id < 0) fail(what);
    return id;
  }
  void ok(herr_t rc, const std::string& what) const {
    if (rc < 0) fail(what);
  }
  void str(hid_t loc, const std::string& name, const std::string& value) const {
    H type(check(H5Tcopy(H5T_C_S1), "string type"), H5Tclose);
    ok(H5Tset_size(type.get(), H5T_VARIABLE), "string type");
    ok(H5Tset_cset(type.get(), H5T_CSET_UTF8), "string type");
    H space(check(H5Screate(H5S_SCALAR), "dataspace"), H5Sclose);
    H attr(check(H5Acreate2(loc, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT), name), H5Aclose);
    const char* data = value.c_str();
    ok(H5Awrite(attr.get(), type.get(), &data), name);
  }
  void num(hid_t loc, const std::string& name, double value) const {
    H space(check(H5Screate(H5S_SCALAR), "dataspace"), H5Sclose);
    H attr(check(H5Acreate2(loc, name.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT), name), H5Aclose);
    ok(H5Awrite(attr.get(), H5T_NATIVE_DOUBLE, &value), name);
  }
  void vec(hid_t loc, const std::string& name, const double* v, int n) const {
    const hsize_t dims[1] = {static_cast<hsize_t>(n)};
    H space(check(H5Screate_simple(1, dims, nullptr), "dataspace"), H5Sclose);
    H attr(check(H5Acreate2(loc, name.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT), name), H5Aclose);
    ok(H5Awrite(attr.get(), H5T_NATIVE_DOUBLE, v), name);
  }
  void data(hid_t loc, const std::string& name, const double* v, hsize_t rows, hsize_t cols, const char* units,
            const char* description) const {
    const hsize_t dims[2] = {rows, cols};
    H space(check(H5Screate_simple(cols == 0 ? 1 : 2, dims, nullptr), "dataspace"), H5Sclose);
    H ds(check(H5Dcreate2(loc, name.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
               "dataset " + name),
         H5Dclose);
    if (rows > 0) ok(H5Dwrite(ds.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v), "dataset " + name);
    str(ds.get(), "units", units);
    str(ds.get(), "description", description);
  }
};

std::string joinNames(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ",") + n;
  return s;
}

void writeGroup(const W& w, hid_t file, const ArmTrajectory& tr) {
  const auto N = static_cast<hsize_t>(tr.samples());
  const int n = static_cast<int>(tr.q.cols());
  if (n != 7 || tr.qd.rows() != tr.samples() || tr.h_ang.cols() != 3 || tr.ee_pos.cols() != 3 ||
      static_cast<int>(tr.joint_names.size()) != n) {
    w.fail("inconsistent arm trajectory (expects 7 joints, N x 3 momentum and end-effector rows)");
  }
  H gcpl(w.check(H5Pcreate(H5P_GROUP_CREATE), "property list"), H5Pclose);
  w.ok(H5Pset_attr_phase_change(gcpl.get(), 1000, 0), "attribute storage");  // compact attributes (see primitive_io)
  H g(w.check(H5Gcreate2(file, tr.name.c_str(), H5P_DEFAULT, gcpl.get(), H5P_DEFAULT), "group " + tr.name), H5Gclose);
  const hid_t gid = g.get();
  w.str(gid, "kind", "arm-trajectory");
  w.str(gid, "joint_names", joinNames(tr.joint_names));
  w.str(gid, "units", "SI: s, m, rad, Nm, N m s; each dataset states its units in attribute 'units'");
  w.str(gid, "frame", tr.reference_frame + " (x forward, y left, z up); torso_2 fixed at its home pose");
  w.str(gid, "ee_frame", tr.ee_frame);
  w.str(gid, "mirror", "right arm: q_right = mirror_signs .* q (joints 2, 3, 5, 7 flip)");
  const auto s = armMirrorSigns();
  w.vec(gid, "mirror_signs", s.data(), 7);
  w.num(gid, "period", tr.period);
  w.vec(gid, "momentum_point", tr.momentum_point.data(), 3);
  w.vec(gid, "ee_box_min", tr.ee_box_min.data(), 3);
  w.vec(gid, "ee_box_max", tr.ee_box_max.data(), 3);
  auto v7 = [&](const char* name, const Eigen::VectorXd& v) {
    if (v.size() != 7) w.fail(std::string("attribute ") + name + " must have 7 values");
    w.vec(gid, name, v.data(), 7);
  };
  v7("q_min", tr.q_min), v7("q_max", tr.q_max), v7("qd_max", tr.qd_max), v7("tau_max", tr.tau_max);
  v7("q_min_model", tr.q_min_model), v7("q_max_model", tr.q_max_model);
  v7("qd_max_model", tr.qd_max_model), v7("tau_max_model", tr.tau_max_model);
  w.str(gid, "solve_status", tr.solve.status);
  w.num(gid, "solve_iterations", tr.solve.iterations);
  w.num(gid, "solve_time_s", tr.solve.solve_time_s);
  w.num(gid, "solve_cost", tr.solve.cost);
  w.num(gid, "solve_max_violation", tr.solve.max_constraint_violation);
  w.str(gid, "config_yaml", tr.config_yaml);

  w.data(gid, "t", tr.t.data(), N, 0, "s", "sample time over one period, t[N-1] = period");
  w.data(gid, "q", tr.q.data(), N, 7, "rad", "joint positions (joint_names order)");
  w.data(gid, "qd", tr.qd.data(), N, 7, "rad/s", "joint velocities");
  w.data(gid, "qdd", tr.qdd.data(), N, 7, "rad/s^2", "joint accelerations (piecewise constant, the OCP control)");
  w.data(gid, "tau", tr.tau.data(), N, 7, "Nm", "joint torques of the fixed-base arm (inverse dynamics, gravity)");
  w.data(gid, "h_ang", tr.h_ang.data(), N, 3, "N m s", "arm angular momentum about momentum_point, pelvis axes");
  w.data(gid, "ee_pos", tr.ee_pos.data(), N, 3, "m", "end-effector (ee_frame) point in the pelvis frame");
  H k(w.check(H5Gcreate2(gid, "knots", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), "group knots"), H5Gclose);
  w.data(k.get(), "t", tr.knot_t.data(), static_cast<hsize_t>(tr.knot_t.size()), 0, "s", "node times");
  w.data(k.get(), "x", tr.knot_x.data(), static_cast<hsize_t>(tr.knot_x.rows()), static_cast<hsize_t>(tr.knot_x.cols()),
         "rad, rad/s", "states [q (7), qd (7)] at the nodes");
  w.data(k.get(), "u", tr.knot_u.data(), static_cast<hsize_t>(tr.knot_u.rows()), static_cast<hsize_t>(tr.knot_u.cols()),
         "rad/s^2", "controls qdd on each interval");
}

// ---- reading ----

struct R {
  std::string path;
  [[noreturn]] void fail(const std::string& key, const std::string& msg) const { throw InputError(path, key, msg); }
  std::vector<double> read(hid_t loc, const std::string& key, const std::string& name, std::vector<hsize_t>& dims) const {
    if (H5Lexists(loc, name.c_str(), H5P_DEFAULT) <= 0) fail(key, "missing dataset");
    H ds(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), H5Dclose);
    if (!ds.valid()) fail(key, "cannot open dataset");
    H space(H5Dget_space(ds.get()), H5Sclose);
    const int rank = space.valid() ? H5Sget_simple_extent_ndims(space.get()) : -1;
    if (rank < 1 || rank > 2) fail(key, "dataset must be 1-D or 2-D");
    dims.assign(static_cast<std::size_t>(rank), 0);
    H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
    hsize_t total = 1;
    for (hsize_t d : dims) total *= d;
    std::vector<double> out(total);
    if (total > 0 && H5Dread(ds.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0) {
      fail(key, "cannot read dataset (corrupt or not numeric?)");
    }
    return out;
  }
  RowMatrix matrix(hid_t loc, const std::string& key, const std::string& name, hsize_t rows, hsize_t cols) const {
    std::vector<hsize_t> d;
    const auto v = read(loc, key, name, d);
    if (d.size() != 2 || (rows != 0 && d[0] != rows) || d[1] != cols) {
      fail(key, "dataset has the wrong shape, expected (" + (rows ? std::to_string(rows) : std::string("N")) + ", " +
                    std::to_string(cols) + ")");
    }
    RowMatrix m(static_cast<Eigen::Index>(d[0]), static_cast<Eigen::Index>(d[1]));
    if (!v.empty()) std::memcpy(m.data(), v.data(), v.size() * sizeof(double));
    return m;
  }
  Eigen::VectorXd vector(hid_t loc, const std::string& key, const std::string& name) const {
    std::vector<hsize_t> d;
    const auto v = read(loc, key, name, d);
    if (d.size() != 1) fail(key, "dataset must be 1-D");
    return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
  }
  bool hasAttr(hid_t loc, const std::string& name) const { return H5Aexists(loc, name.c_str()) > 0; }
  std::vector<double> numbers(hid_t loc, const std::string& key, const std::string& name, int count) const {
    if (!hasAttr(loc, name)) fail(key + "@" + name, "missing attribute");
    H a(H5Aopen(loc, name.c_str(), H5P_DEFAULT), H5Aclose);
    H space(H5Aget_space(a.get()), H5Sclose);
    const hssize_t npts = H5Sget_simple_extent_npoints(space.get());
    if (npts != count) fail(key + "@" + name, "expected " + std::to_string(count) + " numbers");
    std::vector<double> v(static_cast<std::size_t>(count));
    if (H5Aread(a.get(), H5T_NATIVE_DOUBLE, v.data()) < 0) fail(key + "@" + name, "unreadable attribute");
    return v;
  }
  std::string text(hid_t loc, const std::string& key, const std::string& name) const {
    if (!hasAttr(loc, name)) fail(key + "@" + name, "missing attribute");
    H a(H5Aopen(loc, name.c_str(), H5P_DEFAULT), H5Aclose);
    H type(H5Aget_type(a.get()), H5Tclose);
    if (H5Tget_class(type.get()) != H5T_STRING || H5Tis_variable_str(type.get()) <= 0) {
      fail(key + "@" + name, "expected a variable-length string attribute");
    }
    H mem(H5Tcopy(H5T_C_S1), H5Tclose);
    H5Tset_size(mem.get(), H5T_VARIABLE);
    H5Tset_cset(mem.get(), H5Tget_cset(type.get()));
    char* buf = nullptr;
    if (H5Aread(a.get(), mem.get(), &buf) < 0) fail(key + "@" + name, "unreadable attribute");
    std::string s = buf ? buf : "";
    H5free_memory(buf);
    return s;
  }
};

Eigen::VectorXd toVec(const std::vector<double>& v) {
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

}  // namespace

void writeArmTrajectory(const std::string& path, const ArmTrajectory& tr, bool append) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  if (tr.name.empty() || tr.name.find('/') != std::string::npos || tr.name == "." || tr.name == "..") {
    throw RuntimeError("cannot write " + path + ": bad group name '" + tr.name + "'");
  }
  ensureParentDirectory(path);
  const W w{path};
  const std::string tmp = temporaryPathFor(path);
  std::error_code ec;
  const bool keep = append && std::filesystem::exists(path, ec);
  try {
    if (keep) {
      if (H5Fis_hdf5(path.c_str()) <= 0) throw InputError(path + ": not an HDF5 file, cannot append to it");
      std::filesystem::copy_file(path, tmp, std::filesystem::copy_options::overwrite_existing);
      H file(w.check(H5Fopen(tmp.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), "cannot open a copy of " + path), H5Fclose);
      if (H5Lexists(file.get(), tr.name.c_str(), H5P_DEFAULT) > 0) {
        w.ok(H5Ldelete(file.get(), tr.name.c_str(), H5P_DEFAULT), "replacing group " + tr.name);
      }
      writeGroup(w, file.get(), tr);
      if (!file.close()) w.fail("closing (flushing) the file failed");
    } else {
      H fcpl(w.check(H5Pcreate(H5P_FILE_CREATE), "property list"), H5Pclose);
      w.ok(H5Pset_link_creation_order(fcpl.get(), H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED), "creation order");
      H fapl(w.check(H5Pcreate(H5P_FILE_ACCESS), "property list"), H5Pclose);
      w.ok(H5Pset_libver_bounds(fapl.get(), H5F_LIBVER_V18, H5F_LIBVER_V18), "format version");
      H file(w.check(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, fcpl.get(), fapl.get()), "cannot create " + tmp), H5Fclose);
      w.str(file.get(), "format", "centaur-primitive");
      H space(w.check(H5Screate(H5S_SCALAR), "dataspace"), H5Sclose);
      H attr(w.check(H5Acreate2(file.get(), "format_version", H5T_STD_I32LE, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                     "format_version"),
             H5Aclose);
      const int version = kPrimitiveFormatVersion;
      w.ok(H5Awrite(attr.get(), H5T_NATIVE_INT, &version), "format_version");
      attr.close();
      w.str(file.get(), "description", "primitives planned offline by centaur; schema in docs/primitive-format.md");
      writeGroup(w, file.get(), tr);
      if (!file.close()) w.fail("closing (flushing) the file failed");
    }
  } catch (...) {
    removeFileIfExists(tmp);
    throw;
  }
  commitFile(tmp, path);
}

ArmTrajectory readArmTrajectory(const std::string& path, const std::string& name) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(path + ": no such file (write it with `centaur plan arm-flywheel`)");
  const R r{path};
  H file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!file.valid()) throw InputError(path + ": not an HDF5 file or corrupt");
  if (H5Lexists(file.get(), name.c_str(), H5P_DEFAULT) <= 0) r.fail(name, "no such group (an arm trajectory)");
  H g(H5Gopen2(file.get(), name.c_str(), H5P_DEFAULT), H5Gclose);
  if (!g.valid()) r.fail(name, "not a group");
  const hid_t gid = g.get();
  if (r.text(gid, name, "kind") != "arm-trajectory") r.fail(name + "@kind", "is not 'arm-trajectory'");
  ArmTrajectory tr;
  tr.name = name;
  std::stringstream ss(r.text(gid, name, "joint_names"));
  for (std::string item; std::getline(ss, item, ',');) tr.joint_names.push_back(item);
  if (tr.joint_names.size() != 7) r.fail(name + "@joint_names", "expected 7 comma-separated joint names");
  tr.period = r.numbers(gid, name, "period", 1)[0];
  tr.t = r.vector(gid, name + "/t", "t");
  const auto N = static_cast<hsize_t>(tr.t.size());
  if (N < 2) r.fail(name + "/t", "needs at least 2 samples");
  tr.q = r.matrix(gid, name + "/q", "q", N, 7);
  tr.qd = r.matrix(gid, name + "/qd", "qd", N, 7);
  tr.qdd = r.matrix(gid, name + "/qdd", "qdd", N, 7);
  tr.tau = r.matrix(gid, name + "/tau", "tau", N, 7);
  tr.h_ang = r.matrix(gid, name + "/h_ang", "h_ang", N, 3);
  tr.ee_pos = r.matrix(gid, name + "/ee_pos", "ee_pos", N, 3);
  if (H5Lexists(gid, "knots", H5P_DEFAULT) > 0) {
    H k(H5Gopen2(gid, "knots", H5P_DEFAULT), H5Gclose);
    tr.knot_t = r.vector(k.get(), name + "/knots/t", "t");
    tr.knot_x = r.matrix(k.get(), name + "/knots/x", "x", static_cast<hsize_t>(tr.knot_t.size()), 14);
    tr.knot_u = r.matrix(k.get(), name + "/knots/u", "u", 0, 7);
  }
  tr.q_min = toVec(r.numbers(gid, name, "q_min", 7));
  tr.q_max = toVec(r.numbers(gid, name, "q_max", 7));
  tr.qd_max = toVec(r.numbers(gid, name, "qd_max", 7));
  tr.tau_max = toVec(r.numbers(gid, name, "tau_max", 7));
  tr.q_min_model = toVec(r.numbers(gid, name, "q_min_model", 7));
  tr.q_max_model = toVec(r.numbers(gid, name, "q_max_model", 7));
  tr.qd_max_model = toVec(r.numbers(gid, name, "qd_max_model", 7));
  tr.tau_max_model = toVec(r.numbers(gid, name, "tau_max_model", 7));
  tr.momentum_point = toVec(r.numbers(gid, name, "momentum_point", 3));
  tr.ee_box_min = toVec(r.numbers(gid, name, "ee_box_min", 3));
  tr.ee_box_max = toVec(r.numbers(gid, name, "ee_box_max", 3));
  tr.ee_frame = r.text(gid, name, "ee_frame");
  tr.solve.status = r.text(gid, name, "solve_status");
  tr.solve.iterations = static_cast<int>(r.numbers(gid, name, "solve_iterations", 1)[0]);
  tr.solve.solve_time_s = r.numbers(gid, name, "solve_time_s", 1)[0];
  tr.solve.cost = r.numbers(gid, name, "solve_cost", 1)[0];
  tr.solve.max_constraint_violation = r.numbers(gid, name, "solve_max_violation", 1)[0];
  tr.config_yaml = r.text(gid, name, "config_yaml");
  return tr;
}

}  // namespace centaur::planner
