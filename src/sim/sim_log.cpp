#include "sim/sim_log.hpp"

#include <hdf5.h>

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "sim/mujoco_robot.hpp"

namespace centaur::sim {

SimLog::SimLog(std::vector<std::string> joint_names, std::vector<std::string> contact_bodies, std::size_t capacity)
    : joint_names_(std::move(joint_names)),
      contact_bodies_(std::move(contact_bodies)),
      n_(joint_names_.size()),
      nc_(contact_bodies_.size()),
      force_buffer_(3, static_cast<Eigen::Index>(contact_bodies_.size())) {
  t_.reserve(capacity);
  for (auto* v : {&q_, &qd_, &tau_cmd_, &tau_meas_, &tau_applied_, &q_ref_, &qd_ref_, &tau_ff_, &kp_, &kd_}) {
    v->reserve(capacity * n_);
  }
  imu_quat_.reserve(4 * capacity);
  imu_omega_.reserve(3 * capacity);
  imu_acc_.reserve(3 * capacity);
  base_pos_.reserve(3 * capacity);
  base_quat_.reserve(4 * capacity);
  base_vel_.reserve(6 * capacity);
  wheel_force_.reserve(3 * nc_ * capacity);
}

namespace {
void push(std::vector<double>& v, const Eigen::Ref<const Eigen::VectorXd>& x) {
  for (Eigen::Index i = 0; i < x.size(); ++i) v.push_back(x[i]);
}
}  // namespace

void SimLog::appendTruth(const MujocoRobot& robot) {
  push(base_pos_, robot.basePosition());
  const Eigen::Quaterniond bq = robot.baseOrientation();
  base_quat_.insert(base_quat_.end(), {bq.w(), bq.x(), bq.y(), bq.z()});
  push(base_vel_, robot.baseVelocity());
  robot.contactForces(force_buffer_);
  for (Eigen::Index k = 0; k < force_buffer_.cols(); ++k) push(wheel_force_, force_buffer_.col(k));
}

void SimLog::appendLoop(const MujocoRobot& robot, const RobotState& s, const JointCommand& c) {
  t_.push_back(s.t);
  push(q_, s.q);
  push(qd_, s.qd);
  push(tau_cmd_, robot.commandedTorque());
  push(tau_meas_, s.tau);
  push(tau_applied_, robot.appliedTorque());
  push(q_ref_, c.q_ref);
  push(qd_ref_, c.qd_ref);
  push(tau_ff_, c.tau_ff);
  push(kp_, c.kp);
  push(kd_, c.kd);
  imu_quat_.insert(imu_quat_.end(), {s.imu_quat.w(), s.imu_quat.x(), s.imu_quat.y(), s.imu_quat.z()});
  push(imu_omega_, s.imu_omega);
  push(imu_acc_, s.imu_acc);
}

namespace {

void setStringAttribute(hid_t obj, const char* name, const std::string& value) {
  hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, value.empty() ? 1 : value.size());
  H5Tset_strpad(type, H5T_STR_NULLTERM);
  hid_t space = H5Screate(H5S_SCALAR);
  hid_t attr = H5Acreate2(obj, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
  const std::string v = value.empty() ? std::string(1, '\0') : value;
  H5Awrite(attr, type, v.c_str());
  H5Aclose(attr);
  H5Sclose(space);
  H5Tclose(type);
}

void setStringListAttribute(hid_t obj, const char* name, const std::vector<std::string>& values) {
  std::vector<const char*> ptrs;
  for (const auto& v : values) ptrs.push_back(v.c_str());
  hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  const hsize_t dims[1] = {values.size()};
  hid_t space = H5Screate_simple(1, dims, nullptr);
  hid_t attr = H5Acreate2(obj, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
  if (!ptrs.empty()) H5Awrite(attr, type, ptrs.data());
  H5Aclose(attr);
  H5Sclose(space);
  H5Tclose(type);
}

bool writeDataset(hid_t file, const char* name, const std::vector<double>& data, std::vector<hsize_t> dims,
                  const std::string& units, const std::string& description) {
  hid_t space = H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr);
  hid_t ds = H5Dcreate2(file, name, H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  if (ds < 0) {
    H5Sclose(space);
    return false;
  }
  herr_t st = 0;
  if (!data.empty()) st = H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data());
  setStringAttribute(ds, "units", units);
  setStringAttribute(ds, "description", description);
  H5Dclose(ds);
  H5Sclose(space);
  return st >= 0;
}

}  // namespace

void SimLog::writeHdf5(const std::string& path, const std::string& config_yaml, const std::string& scenario) const {
  ensureParentDirectory(path);
  const std::string tmp = temporaryPathFor(path);
  // Silence HDF5's own error printing while writing (errors are reported as RuntimeError); restored below.
  H5E_auto2_t old_func = nullptr;
  void* old_data = nullptr;
  H5Eget_auto2(H5E_DEFAULT, &old_func, &old_data);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  hid_t file = H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (file < 0) {
    H5Eset_auto2(H5E_DEFAULT, old_func, old_data);
    throw RuntimeError("cannot create " + path);
  }
  const hsize_t N = t_.size(), n = n_, nc = nc_;
  bool ok = true;
  ok &= writeDataset(file, "t", t_, {N}, "s", "robot time of the sample (start of the control period)");
  ok &= writeDataset(file, "q", q_, {N, n}, "rad", "measured joint positions (as given to the controller)");
  ok &= writeDataset(file, "qd", qd_, {N, n}, "rad/s", "measured joint velocities (as given to the controller)");
  ok &= writeDataset(file, "tau_cmd", tau_cmd_, {N, n}, "N m",
                     "impedance-law torque before saturation, last physics step of the period");
  ok &= writeDataset(file, "tau_meas", tau_meas_, {N, n}, "N m",
                     "measured joint torques (= applied actuator torques, plus noise if enabled)");
  ok &= writeDataset(file, "tau_applied", tau_applied_, {N, n}, "N m",
                     "actuator torques applied in the period's last physics step (after saturation), ground truth");
  ok &= writeDataset(file, "q_ref", q_ref_, {N, n}, "rad", "controller position reference");
  ok &= writeDataset(file, "qd_ref", qd_ref_, {N, n}, "rad/s", "controller velocity reference");
  ok &= writeDataset(file, "tau_ff", tau_ff_, {N, n}, "N m", "controller torque feed-forward");
  ok &= writeDataset(file, "kp", kp_, {N, n}, "N m/rad", "controller stiffness");
  ok &= writeDataset(file, "kd", kd_, {N, n}, "N m s/rad", "controller damping");
  ok &= writeDataset(file, "imu_quat", imu_quat_, {N, 4}, "-", "IMU orientation w_R_imu, order w, x, y, z");
  ok &= writeDataset(file, "imu_omega", imu_omega_, {N, 3}, "rad/s", "IMU angular velocity, IMU frame");
  ok &= writeDataset(file, "imu_acc", imu_acc_, {N, 3}, "m/s^2", "IMU specific force, IMU frame");
  ok &= writeDataset(file, "base_pos", base_pos_, {N, 3}, "m", "ground truth pelvis position w_p_base at t");
  ok &= writeDataset(file, "base_quat", base_quat_, {N, 4}, "-", "ground truth pelvis orientation, order w, x, y, z");
  ok &= writeDataset(file, "base_vel", base_vel_, {N, 6}, "m/s, rad/s",
                     "ground truth pelvis velocity: linear (world frame), angular (pelvis frame)");
  ok &= writeDataset(file, "wheel_force", wheel_force_, {N, nc, 3}, "N",
                     "ground truth contact force on each contact body (sum of its contacts), world frame, last physics step before t");
  {
    hid_t ds = H5Dopen2(file, "imu_quat", H5P_DEFAULT);
    if (ds >= 0) {
      setStringAttribute(ds, "quaternion_order", "w,x,y,z");
      H5Dclose(ds);
    }
    ds = H5Dopen2(file, "base_quat", H5P_DEFAULT);
    if (ds >= 0) {
      setStringAttribute(ds, "quaternion_order", "w,x,y,z");
      H5Dclose(ds);
    }
  }
  setStringListAttribute(file, "joint_names", joint_names_);
  setStringListAttribute(file, "contact_bodies", contact_bodies_);
  setStringAttribute(file, "config", config_yaml);
  setStringAttribute(file, "scenario", scenario);
  setStringAttribute(file, "format", "centaur-sim-log 1");
  setStringAttribute(file, "units", "SI: s, m, rad, N, N m; quaternions w,x,y,z; see each dataset's `units`");
  ok &= H5Fclose(file) >= 0;
  H5Eset_auto2(H5E_DEFAULT, old_func, old_data);
  if (!ok) {
    removeFileIfExists(tmp);
    throw RuntimeError("cannot write the HDF5 log " + path);
  }
  commitFile(tmp, path);
}

}  // namespace centaur::sim
