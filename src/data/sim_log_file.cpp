#include "data/sim_log_file.hpp"

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "data/hdf5.hpp"

namespace centaur::data {

const std::vector<LogDataset>& simLogDatasets() {
  using C = LogColumns;
  static const std::vector<LogDataset> table = {
      {"t", C::kNone, "s", "robot time of the sample (start of the control period)"},
      {"q", C::kJoints, "rad", "measured joint positions (as given to the controller)"},
      {"qd", C::kJoints, "rad/s", "measured joint velocities (as given to the controller)"},
      {"tau_cmd", C::kJoints, "N m", "impedance-law torque before saturation, last physics step of the period"},
      {"tau_meas", C::kJoints, "N m", "measured joint torques (= applied actuator torques, plus noise if enabled)"},
      {"tau_applied", C::kJoints, "N m",
       "actuator torques applied in the period's last physics step (after saturation), ground truth"},
      {"q_ref", C::kJoints, "rad", "controller position reference"},
      {"qd_ref", C::kJoints, "rad/s", "controller velocity reference"},
      {"tau_ff", C::kJoints, "N m", "controller torque feed-forward"},
      {"kp", C::kJoints, "N m/rad", "controller stiffness"},
      {"kd", C::kJoints, "N m s/rad", "controller damping"},
      {"imu_quat", C::k4, "-", "IMU orientation w_R_imu, order w, x, y, z"},
      {"imu_omega", C::k3, "rad/s", "IMU angular velocity, IMU frame"},
      {"imu_acc", C::k3, "m/s^2", "IMU specific force, IMU frame"},
      {"base_pos", C::k3, "m", "ground truth pelvis position w_p_base at t"},
      {"base_quat", C::k4, "-", "ground truth pelvis orientation, order w, x, y, z"},
      {"base_vel", C::k6, "m/s, rad/s", "ground truth pelvis velocity: linear (world frame), angular (pelvis frame)"},
      {"wheel_force", C::kContacts3, "N",
       "ground truth contact force on each contact body (sum of its contacts), world frame, last physics step "
       "before t"},
  };
  return table;
}

std::vector<unsigned long long> logDatasetDims(const LogDataset& d, const SimLogHeader& h) {
  const unsigned long long N = h.samples;
  switch (d.columns) {
    case LogColumns::kNone: return {N};
    case LogColumns::kJoints: return {N, h.joint_names.size()};
    case LogColumns::k3: return {N, 3};
    case LogColumns::k4: return {N, 4};
    case LogColumns::k6: return {N, 6};
    case LogColumns::kContacts3: return {N, h.contact_bodies.size(), 3};
  }
  return {N};
}

namespace {

std::size_t product(const std::vector<hsize_t>& dims) {
  std::size_t n = 1;
  for (hsize_t d : dims) n *= static_cast<std::size_t>(d);
  return n;
}

void writeFile(const h5::Writer& w, const std::string& tmp, const SimLogHeader& header,
               const std::map<std::string, const std::vector<double>*>& data) {
  h5::Id file = w.createFile(tmp);
  for (const LogDataset& d : simLogDatasets()) {
    const auto it = data.find(d.name);
    const std::vector<hsize_t> dims = logDatasetDims(d, header);
    if (it == data.end() || it->second == nullptr || it->second->size() != product(dims)) {
      w.fail(std::string("dataset '") + d.name + "' is missing or has the wrong number of values");
    }
    // Logs are written once at the end of a run; uncompressed keeps that step fast.
    w.doubles(file.get(), d.name, dims, it->second->data(), {d.units, nullptr, d.description, true}, false);
  }
  for (const char* q : {"imu_quat", "base_quat"}) {
    h5::Id ds(w.check(H5Dopen2(file.get(), q, H5P_DEFAULT), q), H5Dclose);
    w.stringAttribute(ds.get(), "quaternion_order", "w,x,y,z", true);
  }
  w.stringListAttribute(file.get(), "joint_names", header.joint_names);
  w.stringListAttribute(file.get(), "contact_bodies", header.contact_bodies);
  w.stringAttribute(file.get(), "config", header.config_yaml, true);
  w.stringAttribute(file.get(), "scenario", header.scenario, true);
  if (!header.summary_json.empty()) w.stringAttribute(file.get(), "summary", header.summary_json, true);
  w.stringAttribute(file.get(), "format", kSimLogFormat, true);
  w.stringAttribute(file.get(), "units", "SI: s, m, rad, N, N m; quaternions w,x,y,z; see each dataset's `units`",
                    true);
  if (!file.close()) w.fail("closing (flushing) the file failed");
}

}  // namespace

void writeSimLog(const std::string& path, const SimLogHeader& header,
                 const std::map<std::string, const std::vector<double>*>& data) {
  const h5::QuietErrors quiet;
  ensureParentDirectory(path);
  const std::string tmp = temporaryPathFor(path);
  try {
    writeFile(h5::Writer(path), tmp, header, data);
  } catch (...) {
    removeFileIfExists(tmp);
    throw;
  }
  commitFile(tmp, path);
}

// ---- reading -----------------------------------------------------------------------------------------

namespace {
const char* const kExpectedLog = "a simulation log written by `centaur simulate --out`";
}  // namespace

struct SimLogFile::Impl {
  explicit Impl(const std::string& path) : reader(path, kExpectedLog) {}
  explicit Impl(const FileImage& image) : reader(image, kExpectedLog) {}
  h5::Reader reader;
  Eigen::VectorXd t;
};

SimLogFile::SimLogFile(const std::string& path) : impl_(std::make_unique<Impl>(path)) { open(); }

SimLogFile::SimLogFile(const FileImage& image) : impl_(std::make_unique<Impl>(image)) { open(); }

void SimLogFile::open() {
  const h5::Reader& r = impl_->reader;
  const hid_t f = r.file();
  if (!r.hasAttribute(f, "format")) {
    r.fail("format", std::string("missing root attribute: not a centaur simulation log (") + kSimLogFormat + ")");
  }
  const std::string format = r.text(f, "format", "format");
  if (format != kSimLogFormat) {
    r.fail("format", "is '" + format.substr(0, 80) + "': not a centaur simulation log (" + kSimLogFormat + ")");
  }
  header_.joint_names = r.textList(f, "joint_names", "joint_names");
  header_.contact_bodies = r.textList(f, "contact_bodies", "contact_bodies");
  if (header_.joint_names.empty() || header_.joint_names.size() > kMaxLogJoints) {
    r.fail("joint_names", "holds " + std::to_string(header_.joint_names.size()) + " names, allowed [1, " +
                              std::to_string(kMaxLogJoints) + "]");
  }
  if (header_.contact_bodies.size() > kMaxLogJoints) r.fail("contact_bodies", "holds too many names");
  header_.config_yaml = r.text(f, "config", "config");
  header_.scenario = r.text(f, "scenario", "scenario");
  if (r.hasAttribute(f, "summary")) header_.summary_json = r.text(f, "summary", "summary");
  header_.samples = static_cast<std::size_t>(r.length(f, "t", "t", 1, kMaxLogSamples));
  for (const LogDataset& d : simLogDatasets()) {
    const std::vector<hsize_t> want = logDatasetDims(d, header_);
    const std::vector<hsize_t> dims = r.shape(f, d.name, d.name);
    if (dims != want) {
      r.fail(d.name, "dataset has shape " + h5::shapeText(dims) + ", expected " + h5::shapeText(want) +
                         " (N samples of 't', the root attributes' joints and contact bodies)");
    }
  }
  // The time axis is read now (N values): finite and increasing, at most one sample per microsecond.
  impl_->t = r.vector(f, "t", "t", header_.samples);
  r.requireTimeAxis("t", impl_->t, {1, false, false, 1e-6, 1e3});
}

SimLogFile::~SimLogFile() = default;

const std::string& SimLogFile::path() const { return impl_->reader.path(); }

RowMatrix SimLogFile::read(const std::string& name) const {
  for (const LogDataset& d : simLogDatasets()) {
    if (name != d.name) continue;
    const h5::Reader& r = impl_->reader;
    RowMatrix m = r.matrix(r.file(), d.name, d.name, logDatasetDims(d, header_));
    r.requireFinite(d.name, m);
    return m;
  }
  throw InputError(path() + ": '" + name + "' is not a dataset of the simulation log format");
}

Eigen::VectorXd SimLogFile::time() const { return impl_->t; }

}  // namespace centaur::data
