// HDF5 I/O of the arm-flywheel trajectory (see arm_trajectory_io.hpp and docs/primitive-format.md).
#include "data/arm_trajectory_io.hpp"

#include <hdf5.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <vector>

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "data/hdf5.hpp"
#include "data/primitive_io.hpp"

namespace centaur::data {

namespace {

using h5::Id;

/// Writes the group's attributes and datasets (uncompressed: the trajectory is small).
struct W : h5::Writer {
  using h5::Writer::Writer;
  void str(hid_t loc, const std::string& name, const std::string& value) const { stringAttribute(loc, name, value); }
  void num(hid_t loc, const std::string& name, double value) const { doubleAttribute(loc, name, value); }
  void vec(hid_t loc, const std::string& name, const double* v, int n) const {
    vectorAttribute(loc, name, v, static_cast<std::size_t>(n));
  }
  /// cols == 0: a 1-D dataset of `rows` values.
  void data(hid_t loc, const std::string& name, const double* v, hsize_t rows, hsize_t cols, const char* units,
            const char* description) const {
    const std::vector<hsize_t> dims = cols == 0 ? std::vector<hsize_t>{rows} : std::vector<hsize_t>{rows, cols};
    doubles(loc, name, dims, v, {units, nullptr, description}, false);
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
  Id g = w.createGroup(file, tr.name);
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
  if (!tr.solve.backend.empty()) w.str(gid, "solve_backend", tr.solve.backend);
  w.str(gid, "config_yaml", tr.config_yaml);

  w.data(gid, "t", tr.t.data(), N, 0, "s", "sample time over one period, t[N-1] = period");
  w.data(gid, "q", tr.q.data(), N, 7, "rad", "joint positions (joint_names order)");
  w.data(gid, "qd", tr.qd.data(), N, 7, "rad/s", "joint velocities");
  w.data(gid, "qdd", tr.qdd.data(), N, 7, "rad/s^2", "joint accelerations (piecewise constant, the OCP control)");
  w.data(gid, "tau", tr.tau.data(), N, 7, "Nm", "joint torques of the fixed-base arm (inverse dynamics, gravity)");
  w.data(gid, "h_ang", tr.h_ang.data(), N, 3, "N m s", "arm angular momentum about momentum_point, pelvis axes");
  w.data(gid, "ee_pos", tr.ee_pos.data(), N, 3, "m", "end-effector (ee_frame) point in the pelvis frame");
  Id k(w.check(H5Gcreate2(gid, "knots", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), "group knots"), H5Gclose);
  w.data(k.get(), "t", tr.knot_t.data(), static_cast<hsize_t>(tr.knot_t.size()), 0, "s", "node times");
  w.data(k.get(), "x", tr.knot_x.data(), static_cast<hsize_t>(tr.knot_x.rows()), static_cast<hsize_t>(tr.knot_x.cols()),
         "rad, rad/s", "states [q (7), qd (7)] at the nodes");
  w.data(k.get(), "u", tr.knot_u.data(), static_cast<hsize_t>(tr.knot_u.rows()), static_cast<hsize_t>(tr.knot_u.cols()),
         "rad/s^2", "controls qdd on each interval");
}

// ---- reading ----

/// Attribute keys in messages read "<group>@<attribute>".
struct R : h5::Reader {
  using h5::Reader::Reader;
  RowMatrix matrix(hid_t loc, const std::string& key, const std::string& name, hsize_t rows, hsize_t cols) const {
    return h5::Reader::matrix(loc, key, name, {rows, cols});
  }
  Eigen::VectorXd vector(hid_t loc, const std::string& key, const std::string& name) const {
    return h5::Reader::vector(loc, key, name, 0);
  }
  std::vector<double> numbers(hid_t loc, const std::string& key, const std::string& name, int count) const {
    return h5::Reader::numbers(loc, key + "@" + name, name, static_cast<std::size_t>(count));
  }
  std::string text(hid_t loc, const std::string& key, const std::string& name) const {
    return h5::Reader::text(loc, key + "@" + name, name);
  }
};

Eigen::VectorXd toVec(const std::vector<double>& v) {
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

}  // namespace

void writeArmTrajectory(const std::string& path, const ArmTrajectory& tr, bool append) {
  const h5::QuietErrors quiet;
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
      if (!std::filesystem::is_regular_file(path, ec) || H5Fis_hdf5(path.c_str()) <= 0) {
        throw InputError(path + ": not an HDF5 file, cannot append to it");
      }
      std::filesystem::copy_file(path, tmp, std::filesystem::copy_options::overwrite_existing);
      Id file = w.openFile(tmp);
      if (H5Lexists(file.get(), tr.name.c_str(), H5P_DEFAULT) > 0) {
        w.ok(H5Ldelete(file.get(), tr.name.c_str(), H5P_DEFAULT), "replacing group " + tr.name);
      }
      writeGroup(w, file.get(), tr);
      if (!file.close()) w.fail("closing (flushing) the file failed");
    } else {
      Id file = w.createFile(tmp);
      w.str(file.get(), "format", "centaur-primitive");
      w.intAttribute(file.get(), "format_version", kPrimitiveFormatVersion);
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

namespace {

constexpr hsize_t kMaxArmSamples = 1000001;  // 100 s at 0.1 ms: beyond any sample_dt and period the planner takes

/// Bounds of the OCP: finite, lower < upper where they pair up, limits > 0.
void checkBounds(const R& r, const std::string& name, const ArmTrajectory& tr) {
  auto finite = [&](const char* attr, const Eigen::VectorXd& v) { r.requireFinite(name + "@" + attr, v); };
  finite("q_min", tr.q_min), finite("q_max", tr.q_max), finite("qd_max", tr.qd_max), finite("tau_max", tr.tau_max);
  finite("q_min_model", tr.q_min_model), finite("q_max_model", tr.q_max_model);
  finite("qd_max_model", tr.qd_max_model), finite("tau_max_model", tr.tau_max_model);
  r.requireFinite(name + "@momentum_point", tr.momentum_point.data(), 3, 1);
  r.requireFinite(name + "@ee_box_min", tr.ee_box_min.data(), 3, 1);
  r.requireFinite(name + "@ee_box_max", tr.ee_box_max.data(), 3, 1);
  for (int j = 0; j < 7; ++j) {
    if (!(tr.q_min[j] < tr.q_max[j])) r.fail(name + "@q_min", "must be below q_max for every joint");
    if (!(tr.q_min_model[j] < tr.q_max_model[j])) r.fail(name + "@q_min_model", "must be below q_max_model");
    if (!(tr.qd_max[j] > 0.0 && tr.tau_max[j] > 0.0 && tr.qd_max_model[j] > 0.0 && tr.tau_max_model[j] > 0.0)) {
      r.fail(name + "@qd_max", "velocity and torque limits must be > 0");
    }
  }
}

ArmTrajectory readTrajectory(const R& r, const std::string& name) {
  if (!r.exists(r.file(), name)) r.fail(name, "no such group (an arm trajectory)");
  Id g(H5Gopen2(r.file(), name.c_str(), H5P_DEFAULT), H5Gclose);
  if (!g.valid() || H5Iget_type(g.get()) != H5I_GROUP) r.fail(name, "not a group");
  const hid_t gid = g.get();
  if (r.text(gid, name, "kind") != "arm-trajectory") r.fail(name + "@kind", "is not 'arm-trajectory'");
  ArmTrajectory tr;
  tr.name = name;
  std::stringstream ss(r.text(gid, name, "joint_names"));
  for (std::string item; std::getline(ss, item, ',');) tr.joint_names.push_back(item);
  if (tr.joint_names.size() != 7) r.fail(name + "@joint_names", "expected 7 comma-separated joint names");
  tr.period = r.numbers(gid, name, "period", 1)[0];
  if (!(tr.period >= 0.01 && tr.period <= 100.0)) r.fail(name + "@period", "must be a number in [0.01, 100] s");
  const hsize_t N = r.length(gid, name + "/t", "t", 2, kMaxArmSamples);
  tr.t = r.vector(gid, name + "/t", "t");
  r.requireTimeAxis(name + "/t", tr.t, {2, true, true, 1e-5, 1.0});
  if (std::abs(tr.t[tr.t.size() - 1] - tr.period) > 1e-6 * (tr.t[1] - tr.t[0])) {
    r.fail(name + "/t", "ends at " + std::to_string(tr.t[tr.t.size() - 1]) + " s, not at the period " +
                            std::to_string(tr.period) + " s");
  }
  auto matrix = [&](const std::string& key, const char* dataset, hsize_t rows, hsize_t cols) {
    RowMatrix m = r.matrix(g.get(), key, dataset, rows, cols);
    r.requireFinite(key, m);
    return m;
  };
  tr.q = matrix(name + "/q", "q", N, 7);
  tr.qd = matrix(name + "/qd", "qd", N, 7);
  tr.qdd = matrix(name + "/qdd", "qdd", N, 7);
  tr.tau = matrix(name + "/tau", "tau", N, 7);
  tr.h_ang = matrix(name + "/h_ang", "h_ang", N, 3);
  tr.ee_pos = matrix(name + "/ee_pos", "ee_pos", N, 3);
  if (r.exists(gid, "knots")) {
    const Id k = r.openGroup(gid, name + "/knots", "knots");
    const hsize_t nk = r.length(k.get(), name + "/knots/t", "t", 2, kMaxArmSamples);
    tr.knot_t = r.vector(k.get(), name + "/knots/t", "t");
    r.requireTimeAxis(name + "/knots/t", tr.knot_t, {2, true, false, 1e-6, 100.0});
    tr.knot_x = r.matrix(k.get(), name + "/knots/x", "x", nk, 14);
    tr.knot_u = r.matrix(k.get(), name + "/knots/u", "u", nk - 1, 7);
    r.requireFinite(name + "/knots/x", tr.knot_x);
    r.requireFinite(name + "/knots/u", tr.knot_u);
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
  checkBounds(r, name, tr);
  tr.ee_frame = r.text(gid, name, "ee_frame");
  tr.solve.status = r.text(gid, name, "solve_status");
  const double iterations = r.numbers(gid, name, "solve_iterations", 1)[0];
  if (!(iterations >= 0.0 && iterations <= 1e9)) r.fail(name + "@solve_iterations", "must be an integer >= 0");
  tr.solve.iterations = static_cast<int>(iterations);
  tr.solve.solve_time_s = r.numbers(gid, name, "solve_time_s", 1)[0];
  tr.solve.cost = r.numbers(gid, name, "solve_cost", 1)[0];
  tr.solve.max_constraint_violation = r.numbers(gid, name, "solve_max_violation", 1)[0];
  if (r.hasAttribute(gid, "solve_backend")) tr.solve.backend = r.text(gid, name, "solve_backend");
  tr.config_yaml = r.text(gid, name, "config_yaml");
  return tr;
}

const char* const kExpectedArm = "an arm trajectory written by `centaur plan arm-flywheel`";

}  // namespace

ArmTrajectory readArmTrajectory(const std::string& path, const std::string& name) {
  return readTrajectory(R(path, kExpectedArm), name);
}

ArmTrajectory readArmTrajectory(const FileImage& image, const std::string& name) {
  return readTrajectory(R(image, kExpectedArm), name);
}

}  // namespace centaur::data
