#include "data/primitive_io.hpp"

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
#include "common/excerpt.hpp"
#include "data/hdf5.hpp"
#include "data/sim_log_file.hpp"
#include "data/solver_multipliers_io.hpp"

namespace centaur::data {
namespace {

constexpr hsize_t kNq = 19;     // template q: p(3), quat w,x,y,z (4), q_C (12)
constexpr hsize_t kNv = 18;     // template nu: v(3), omega(3), qdot_C (12)
constexpr hsize_t kFeet = 4;
constexpr hsize_t kJoints = 12;
constexpr hsize_t kNuControls = 31;         // knot controls: nu_dot (18), F (12), dt (1)
constexpr hsize_t kMaxSamples = 300000;     // 300 s at 1 kHz: far beyond any primitive, bounds the memory
constexpr hsize_t kMaxKnots = 100000;

// Group attributes the library owns; Primitive::scalars/vectors/strings may not use these names.
const std::set<std::string>& reservedAttributes() {
  static const std::set<std::string> names = {
      "solve_status", "solve_iterations", "solve_time_s", "final_cost", "max_constraint_violation", "solve_backend",
      "config_yaml",  "foot_order",       "quaternion_order", "units",  "force_convention",
      "frames",       "format",           "format_version"};
  return names;
}

using h5::Id;
using Writer = h5::Writer;
using Meta = h5::DatasetMeta;

// =====================================================================================================
// Writing
// =====================================================================================================

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

// The 1 kHz samples: one dataset per quantity, with its units, frame and meaning.
void writeSamples(const Writer& w, hid_t gid, const Primitive& p) {
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
    Id ds(w.check(H5Dopen2(gid, "base_quat", H5P_DEFAULT), "dataset 'base_quat'"), H5Dclose);
    w.stringAttribute(ds.get(), "order", "w,x,y,z");
  }
}

// The OCP's knots (group `knots`): node times, states, controls, interval durations, the solver's multipliers.
void writeKnots(const Writer& w, hid_t gid, const Primitive& p) {
  Id k(w.check(H5Gcreate2(gid, "knots", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), "group 'knots'"), H5Gclose);
  const Eigen::Index nk = p.knot_t.size();
  const Eigen::Index ns = nk > 0 ? nk - 1 : 0;
  writeVector(w, k.get(), p, "t", p.knot_t, nk, {"s", nullptr, "node times t_k (N_s + 1)"});
  writeMatrix(w, k.get(), p, "x", p.knot_x, nk, {static_cast<hsize_t>(p.knot_x.cols())},
              {"SI", "see q, nu", "OCP states x_k = [q_k, nu_k] at the nodes"});
  writeMatrix(w, k.get(), p, "u", p.knot_u, ns, {static_cast<hsize_t>(p.knot_u.cols())},
              {"SI", "W (nu_dot base, forces), B (qddot_C)",
               "OCP controls u_k, piecewise constant over each interval"});
  writeVector(w, k.get(), p, "dt", p.knot_dt, ns, {"s", nullptr, "interval durations dt_k (N_s)"});
  writeSolverMultipliers(w, k.get(), p);
}

// The metadata attributes: the caller's scalars, vectors and strings (one namespace), the solve's figures and the
// conventions.
void writeMetadata(const Writer& w, hid_t gid, const Primitive& p) {
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
  if (!p.solve.backend.empty()) w.stringAttribute(gid, "solve_backend", p.solve.backend);
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

void writeGroup(const Writer& w, hid_t file, const Primitive& p) {
  Id g = w.createGroup(file, p.name);
  writeSamples(w, g.get(), p);
  writeKnots(w, g.get(), p);
  writeMetadata(w, g.get(), p);
}

void checkName(const std::string& target, const std::string& name) {
  if (name.empty() || name == "." || name.find('/') != std::string::npos) {
    throw RuntimeError("cannot write " + target + ": primitive name '" + name +
                       "' is not a valid HDF5 group name (non-empty, no '/')");
  }
}

void writeFile(const std::string& tmp, const std::string& target, const std::vector<const Primitive*>& prims) {
  const Writer w(target);
  Id file = w.createFile(tmp);
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

const char* const kExpected = "an HDF5 primitive file written by `centaur plan`";

/// The primitive file's reader: h5::Reader plus the format check and the group listing that skips other kinds
/// of groups.
class Reader : public h5::Reader {
 public:
  explicit Reader(const std::string& path) : h5::Reader(path, kExpected) { checkFormat(); }
  explicit Reader(const FileImage& image) : h5::Reader(image, kExpected) { checkFormat(); }

  /// A file that says what it is must say "centaur-primitive" (a simulation log is recognised as one); files
  /// written by other tools may omit the root attributes.
  void checkFormat() const {
    if (hasAttribute(file(), "format")) {
      const h5::AttributeValue v = attribute(file(), "format", "format");
      if (v.kind != h5::AttributeValue::kString) fail("format", "root attribute is not a string");
      if (v.text == kSimLogFormat) {
        fail("format", std::string("this is a simulation log (") + kSimLogFormat +
                           ", written by `centaur simulate --out`), not a primitive file");
      }
      if (v.text != "centaur-primitive") {
        fail("format", "is '" + excerpt(v.text) + "': not a centaur primitive file (format 'centaur-primitive')");
      }
    }
    if (hasAttribute(file(), "format_version")) {
      const std::vector<double> version = numbers(file(), "format_version", "format_version", 1);
      if (!(version[0] >= 1 && version[0] <= kPrimitiveFormatVersion)) {
        fail("format_version", "is " + std::to_string(version[0]) + "; this centaur reads versions 1 to " +
                                   std::to_string(kPrimitiveFormatVersion));
      }
    }
  }

  /// Lower-body primitive groups: other kinds of groups may share the file (e.g. an arm-flywheel
  /// trajectory, attribute kind = "arm-trajectory"); lower-body primitives have no `kind` attribute.
  std::vector<std::string> groupNames() const {
    std::vector<std::string> primitives;
    for (const std::string& n : childGroups(file())) {
      Id gid(H5Gopen2(file(), n.c_str(), H5P_DEFAULT), H5Gclose);
      if (gid.valid() && H5Aexists(gid.get(), "kind") > 0) continue;
      primitives.push_back(n);
    }
    return primitives;
  }
};

using h5::AttributeValue;

struct AttributeSink {
  Primitive* prim;
  std::vector<std::string> bad;  // reserved attributes of the wrong type
};

herr_t collectAttribute(hid_t loc, const char* name, const H5A_info_t* /*info*/, void* data) {
  auto* sink = static_cast<AttributeSink*>(data);
  Primitive& p = *sink->prim;
  Id attr(H5Aopen(loc, name, H5P_DEFAULT), H5Aclose);
  if (!attr.valid()) return 0;
  const AttributeValue v = h5::readAttribute(attr.get());
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
    const bool integer = is_scalar && v.numbers[0] >= 0.0 && v.numbers[0] <= 1e9 && std::floor(v.numbers[0]) == v.numbers[0];
    if (expect(integer)) p.solve.iterations = static_cast<int>(v.numbers[0]);
  } else if (key == "solve_time_s") {
    if (expect(is_scalar)) p.solve.solve_time_s = v.numbers[0];
  } else if (key == "final_cost") {
    if (expect(is_scalar)) p.solve.cost = v.numbers[0];
  } else if (key == "max_constraint_violation") {
    if (expect(is_scalar)) p.solve.max_constraint_violation = v.numbers[0];
  } else if (key == "solve_backend") {
    if (expect(is_string)) p.solve.backend = v.text;
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

/// The knots (raw OCP solution): empty, or consistent node times, steps and sizes.
void readKnots(const Reader& r, hid_t gid, const std::string& k, Primitive& p) {
  const std::string kk = k + "knots/";
  const Id knots = r.openGroup(gid, k + "knots", "knots");
  const hsize_t nk = r.length(knots.get(), kk + "t", "t", 0, kMaxKnots);
  if (nk == 1) r.fail(kk + "t", "holds one node: the knots are empty or hold at least two nodes");
  const hsize_t ns = nk > 0 ? nk - 1 : 0;
  if (nk == 0) {
    // No nodes: the other knot datasets must be empty as well. (A 0 in the shapes asked of the reader below
    // means "any", which would let a file declare up to the reader's limit of values there.)
    for (const char* dataset : {"x", "u", "dt"}) {
      const std::vector<hsize_t> dims = r.shape(knots.get(), kk + dataset, dataset);
      if (std::find(dims.begin(), dims.end(), hsize_t{0}) == dims.end()) {  // no zero extent: holds values
        r.fail(kk + dataset, "holds values but knots/t has no nodes: empty knots are empty throughout");
      }
    }
  }
  p.knot_t = r.vector(knots.get(), kk + "t", "t", nk);
  p.knot_x = r.matrix(knots.get(), kk + "x", "x", {nk, nk > 0 ? kNq + kNv : 0});
  p.knot_u = r.matrix(knots.get(), kk + "u", "u", {ns, nk > 0 ? kNuControls : 0});
  p.knot_dt = r.vector(knots.get(), kk + "dt", "dt", ns);
  r.requireFinite(kk + "x", p.knot_x);
  r.requireFinite(kk + "u", p.knot_u);
  r.requireFinite(kk + "dt", p.knot_dt);
  readSolverMultipliers(r, knots.get(), kk, p);
  if (nk == 0) return;
  r.requireTimeAxis(kk + "t", p.knot_t, {2, true, false, 1e-6, 100.0});
  const double scale = 1e-9 * (1.0 + std::abs(p.knot_t[static_cast<Eigen::Index>(ns)]));
  for (Eigen::Index i = 0; i < static_cast<Eigen::Index>(ns); ++i) {
    if (std::abs(p.knot_t[i + 1] - p.knot_t[i] - p.knot_dt[i]) > scale) {
      r.fail(kk + "dt", "interval " + std::to_string(i) + " differs from the step of knots/t");
    }
  }
  const double t_end = p.t[p.t.size() - 1], knots_end = p.knot_t[static_cast<Eigen::Index>(ns)];
  const double step = p.t[1] - p.t[0];
  if (t_end > knots_end + 1e-9 || knots_end - t_end > step + 1e-9) {
    r.fail(kk + "t", "the knots end at " + std::to_string(knots_end) + " s but the samples at " +
                         std::to_string(t_end) + " s (the samples span the knots)");
  }
}

/// The solver outcome and the model metadata: typed, finite where numbers are read.
void checkMetadata(const Reader& r, const std::string& k, const Primitive& p) {
  if (!(p.solve.iterations >= 0)) r.fail(k + "solve_iterations", "must be an integer >= 0");
  if (!(p.solve.solve_time_s >= 0.0 && std::isfinite(p.solve.solve_time_s))) {
    r.fail(k + "solve_time_s", "must be a finite number >= 0");
  }
  for (const auto& [key, value] : p.scalars) {
    if (!std::isfinite(value)) r.fail(k + key, "metadata value is not a finite number");
  }
  for (const auto& [key, values] : p.vectors) {
    for (double v : values) {
      if (!std::isfinite(v)) r.fail(k + key, "metadata vector holds a value that is not a finite number");
    }
  }
}

Primitive readGroup(const Reader& r, const std::string& name) {
  Id g(H5Gopen2(r.file(), name.c_str(), H5P_DEFAULT), H5Gclose);
  if (!g.valid()) r.fail(name, "cannot open group (corrupt?)" + h5::errorStackMessage());
  const hid_t gid = g.get();
  Primitive p;
  p.name = name;
  const std::string k = name + "/";
  // The sample count is checked before anything is read; every dataset is read and checked in turn.
  const hsize_t n = r.length(gid, k + "t", "t", 2, kMaxSamples);
  p.t = r.vector(gid, k + "t", "t", n);
  r.requireTimeAxis(k + "t", p.t, h5::TimeAxisRules{});
  auto matrix = [&](const char* dataset, const std::vector<hsize_t>& shape) {
    RowMatrix m = r.matrix(gid, k + dataset, dataset, shape);
    r.requireFinite(k + dataset, m);
    return m;
  };
  p.q = matrix("q", {n, kNq});
  p.nu = matrix("nu", {n, kNv});
  p.base_pos = matrix("base_pos", {n, 3});
  p.base_quat = matrix("base_quat", {n, 4});
  r.requireUnitQuaternions(k + "base_quat", p.base_quat);
  p.base_vel = matrix("base_vel", {n, 3});
  p.base_omega = matrix("base_omega", {n, 3});
  p.foot_pos = matrix("foot_pos", {n, kFeet, 3});
  p.foot_pos_rel = matrix("foot_pos_rel", {n, kFeet, 3});
  p.foot_vel_rel = matrix("foot_vel_rel", {n, kFeet, 3});
  p.force = matrix("force", {n, kFeet, 3});
  p.contact = r.matrix(gid, k + "contact", "contact", {n, kFeet});
  for (Eigen::Index i = 0; i < p.contact.size(); ++i) {
    const double c = p.contact.data()[i];
    if (c != 0.0 && c != 1.0) r.fail(k + "contact", "holds " + std::to_string(c) + ", allowed values are 0 and 1");
  }
  p.tau = matrix("tau", {n, kJoints});
  readKnots(r, gid, k, p);

  AttributeSink sink{&p, {}};
  hsize_t idx = 0;
  if (H5Aiterate2(gid, H5_INDEX_NAME, H5_ITER_INC, &idx, collectAttribute, &sink) < 0) {
    r.fail(name, "cannot read the group attributes (corrupt?)" + h5::errorStackMessage());
  }
  if (!sink.bad.empty()) r.fail(k + sink.bad.front(), "attribute has the wrong type or value");
  checkMetadata(r, k, p);
  return p;
}

}  // namespace

// =====================================================================================================
// Public API
// =====================================================================================================

void writePrimitives(const std::string& path, const std::vector<Primitive>& prims, WriteMode mode) {
  const h5::QuietErrors quiet;
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

namespace {

std::vector<Primitive> readAll(const Reader& r) {
  std::vector<Primitive> out;
  for (const std::string& name : r.groupNames()) out.push_back(readGroup(r, name));
  return out;
}

Primitive readOne(const Reader& r, const std::string& name) {
  const std::vector<std::string> names = r.groupNames();
  if (std::find(names.begin(), names.end(), name) == names.end()) {
    std::string available;
    for (std::size_t i = 0; i < names.size() && i < 20; ++i) available += (i ? ", " : "") + excerpt(names[i]);
    if (names.size() > 20) available += " and " + std::to_string(names.size() - 20) + " more";
    r.fail(name, "no such primitive; the file holds: " + (available.empty() ? std::string("none") : available));
  }
  return readGroup(r, name);
}

}  // namespace

std::vector<std::string> listPrimitives(const std::string& path) { return Reader(path).groupNames(); }
std::vector<std::string> listPrimitives(const FileImage& image) { return Reader(image).groupNames(); }
std::vector<Primitive> readPrimitives(const std::string& path) { return readAll(Reader(path)); }
std::vector<Primitive> readPrimitives(const FileImage& image) { return readAll(Reader(image)); }
Primitive readPrimitive(const std::string& path, const std::string& name) { return readOne(Reader(path), name); }

void requirePlannedFor(const Primitive& p, const std::string& robot, const std::string& where) {
  const auto it = p.strings.find("robot");
  const std::string planned = it == p.strings.end() ? std::string("centauro") : it->second;
  if (planned != robot) {
    throw InputError(where + ": planned for robot '" + excerpt(planned) + "', but this run drives robot '" +
                     excerpt(robot) + "': plan it for '" + excerpt(robot) + "' (key robot)");
  }
}
Primitive readPrimitive(const FileImage& image, const std::string& name) { return readOne(Reader(image), name); }

}  // namespace centaur::data
