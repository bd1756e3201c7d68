#include "sim/mujoco_robot.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "common/error.hpp"
#include "model/mjcf_load.hpp"

namespace centaur::sim {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}

MujocoRobot::MujocoRobot(const SimSettings& settings) : settings_(settings), rng_(settings.seed) {
  m_ = settings_.scene_xml.empty() ? loadMjcf(settings_.model_path, !settings_.visual_geoms)
                                   : loadMjcfInScene(settings_.model_path, settings_.scene_xml);
  configureModel();
  d_ = mj_makeData(m_);
  readActuators();
  findBaseAndSensors();
  setContactsAndWall();
  checkPush();
  if (settings_.mass_scale != 1.0 || !settings_.com_offset.isZero(0.0)) applyModelError();

  command_.resize(n_);
  tau_applied_.setZero(n_);
  tau_cmd_.setZero(n_);
  delay_.resize(static_cast<std::size_t>(settings_.latency_periods) + 1);
  for (auto& s : delay_) s.resize(n_);
  reset();
}

// The integrator, the time step and the contact solver of the settings (the model is deleted on bad input).
void MujocoRobot::configureModel() {
  const std::string& path = settings_.model_path;
  if (m_->opt.integrator == mjINT_RK4) {
    mj_deleteModel(m_);
    throw InputError(path + ": the RK4 integrator is not supported (the impedance law needs mj_step1/mj_step2)");
  }
  if (!(settings_.timestep > 0.0) || settings_.control_decimation < 1 || settings_.latency_periods < 0) {
    mj_deleteModel(m_);
    throw InputError(path + ": invalid simulation timing (timestep > 0, control_decimation >= 1, latency >= 0)");
  }
  m_->opt.timestep = settings_.timestep;
  if (settings_.solver == "newton") {
    m_->opt.solver = mjSOL_NEWTON;
  } else if (settings_.solver == "cg") {
    m_->opt.solver = mjSOL_CG;
  } else if (settings_.solver == "pgs") {
    m_->opt.solver = mjSOL_PGS;
  } else if (settings_.solver != "model") {
    mj_deleteModel(m_);
    throw InputError(path + ": unknown contact solver '" + settings_.solver + "' (newton, cg, pgs or model)");
  }
}

// The actuated joints, in the model's joint order (the controller's), each with the torque motor that drives it:
// motors are matched to joints by the joint they act on, never by their order. Gears, effort and position limits
// (model and data are deleted on bad input).
void MujocoRobot::readActuators() {
  const std::string& path = settings_.model_path;
  auto fail = [&](const std::string& msg) {
    mj_deleteData(d_);
    mj_deleteModel(m_);
    throw InputError(path + ": " + msg);
  };
  std::vector<int> motor_of_joint(m_->njnt, -1);
  for (int i = 0; i < m_->nu; ++i) {
    const int j = m_->actuator_trnid[2 * i];
    const char* name = mj_id2name(m_, mjOBJ_ACTUATOR, i);
    if (m_->actuator_trntype[i] != mjTRN_JOINT || j < 0 ||
        (m_->jnt_type[j] != mjJNT_HINGE && m_->jnt_type[j] != mjJNT_SLIDE) || m_->actuator_dyntype[i] != mjDYN_NONE ||
        m_->actuator_gaintype[i] != mjGAIN_FIXED || m_->actuator_biastype[i] != mjBIAS_NONE) {
      fail("actuator '" + (name ? std::string(name) : std::to_string(i)) + "' must be a torque motor on a hinge or slide joint");
    }
    if (motor_of_joint[j] >= 0) fail("joint '" + std::string(mj_id2name(m_, mjOBJ_JOINT, j)) + "' has two motors");
    motor_of_joint[j] = i;
  }
  n_ = m_->nu;
  gear_.resize(n_);
  tau_max_.resize(n_);
  q_lo_.resize(n_);
  q_hi_.resize(n_);
  int k = 0;
  for (int j = 0; j < m_->njnt; ++j) {
    const int i = motor_of_joint[j];
    if (i < 0) continue;
    const char* jname = mj_id2name(m_, mjOBJ_JOINT, j);
    joint_names_.emplace_back(jname ? jname : "joint" + std::to_string(j));
    motor_.push_back(i);
    qpos_adr_.push_back(m_->jnt_qposadr[j]);
    dof_adr_.push_back(m_->jnt_dofadr[j]);
    const double gear = m_->actuator_gear[6 * i] * m_->actuator_gainprm[mjNGAIN * i];
    gear_[k] = gear;
    tau_max_[k] = m_->actuator_ctrllimited[i]
                      ? std::min(std::abs(m_->actuator_ctrlrange[2 * i]), std::abs(m_->actuator_ctrlrange[2 * i + 1])) *
                            std::abs(gear)
                      : kInf;
    q_lo_[k] = m_->jnt_limited[j] ? m_->jnt_range[2 * j] : -kInf;
    q_hi_[k] = m_->jnt_limited[j] ? m_->jnt_range[2 * j + 1] : kInf;
    ++k;
  }
}

// The floating base's coordinates, the IMU's sensors and the keyframe.
void MujocoRobot::findBaseAndSensors() {
  for (int j = 0; j < m_->njnt; ++j) {
    if (m_->jnt_type[j] == mjJNT_FREE) {
      base_qpos_ = m_->jnt_qposadr[j];
      base_dof_ = m_->jnt_dofadr[j];
      break;
    }
  }
  sensor_quat_ = mj_name2id(m_, mjOBJ_SENSOR, settings_.imu_orientation.c_str());
  sensor_gyro_ = mj_name2id(m_, mjOBJ_SENSOR, settings_.imu_gyro.c_str());
  sensor_acc_ = mj_name2id(m_, mjOBJ_SENSOR, settings_.imu_accelerometer.c_str());
  key_ = settings_.keyframe.empty() ? -1 : mj_name2id(m_, mjOBJ_KEY, settings_.keyframe.c_str());
}

// The contact bodies (ground-truth forces), the friction of their geoms and the ground's, and the wall's position
// (model and data are deleted on bad input).
void MujocoRobot::setContactsAndWall() {
  const std::string& path = settings_.model_path;
  for (const auto& b : settings_.contact_bodies) {
    const int id = mj_name2id(m_, mjOBJ_BODY, b.c_str());
    if (id < 0) {
      mj_deleteData(d_);
      mj_deleteModel(m_);
      throw InputError(path + ": contact body '" + b + "' not found in the model");
    }
    contact_body_ids_.push_back(id);
  }
  // Friction: MuJoCo uses the maximum of the two geoms' coefficients, so set both sides.
  const int ground = mj_name2id(m_, mjOBJ_GEOM, "ground");
  if (ground >= 0) m_->geom_friction[3 * ground] = settings_.friction;
  for (int g = 0; g < m_->ngeom; ++g) {
    if (std::find(contact_body_ids_.begin(), contact_body_ids_.end(), m_->geom_bodyid[g]) != contact_body_ids_.end()) {
      m_->geom_friction[3 * g] = settings_.friction;
    }
  }
  // Wall: body `wall` whose front face (normal +x, towards the robot) is at body_pos.x (CENTAURO's MJCF
  // convention), or else a world box geom `wall` whose +x face is placed at wall_x.
  const int wall_body = mj_name2id(m_, mjOBJ_BODY, "wall");
  const int wall_geom = mj_name2id(m_, mjOBJ_GEOM, "wall");
  if (wall_body > 0) {
    m_->body_pos[3 * wall_body] = settings_.wall_x;
  } else if (wall_geom >= 0 && m_->geom_bodyid[wall_geom] == 0) {
    m_->geom_pos[3 * wall_geom] = settings_.wall_x - m_->geom_size[3 * wall_geom];
  }
}

// The push's body, duration and direction (model and data are deleted on bad input).
void MujocoRobot::checkPush() {
  const std::string& path = settings_.model_path;
  if (settings_.push.impulse > 0.0) {
    push_body_ = mj_name2id(m_, mjOBJ_BODY, settings_.push.body.c_str());
    if (push_body_ <= 0 || !(settings_.push.duration > 0.0) || !(settings_.push.direction.norm() > 0.0)) {
      mj_deleteData(d_);
      mj_deleteModel(m_);
      throw InputError(path + ": push.body '" + settings_.push.body +
                       "' is not a body of the model (or push.duration / push.direction is zero)");
    }
    settings_.push.direction.normalize();
  }
}

void MujocoRobot::applyModelError() {
  if (base_dof_ < 0 || !(settings_.mass_scale > 0.0)) {
    mj_deleteData(d_);
    mj_deleteModel(m_);
    throw InputError(settings_.model_path +
                     ": robot.mass_scale / robot.com_offset need a floating-base robot and a positive scale");
  }
  int base_body = -1;
  for (int j = 0; j < m_->njnt; ++j) {
    if (m_->jnt_type[j] == mjJNT_FREE) base_body = m_->jnt_bodyid[j];
  }
  const int root = m_->body_rootid[base_body];
  double total = 0.0;
  for (int b = 1; b < m_->nbody; ++b) {
    if (m_->body_rootid[b] != root) continue;  // the world's other bodies (ground, wall) keep their masses
    m_->body_mass[b] *= settings_.mass_scale;
    for (int k = 0; k < 3; ++k) m_->body_inertia[3 * b + k] *= settings_.mass_scale;
    total += m_->body_mass[b];
  }
  // Moving the base body's CoM by d * M / m_base moves the whole robot's CoM by d (the base frame's axes).
  if (m_->body_mass[base_body] > 0.0 && !settings_.com_offset.isZero(0.0)) {
    for (int k = 0; k < 3; ++k) {
      m_->body_ipos[3 * base_body + k] += settings_.com_offset[k] * total / m_->body_mass[base_body];
    }
    // MuJoCo's shortcuts for frames that coincide with the inertial frame no longer hold: the geoms and sites
    // stay where they were on the body (their offsets are relative to the body frame).
    m_->body_sameframe[base_body] = 0;
    for (int g = 0; g < m_->ngeom; ++g) {
      if (m_->geom_bodyid[g] == base_body && m_->geom_sameframe[g] == 2) m_->geom_sameframe[g] = 0;
    }
    for (int i = 0; i < m_->nsite; ++i) {
      if (m_->site_bodyid[i] == base_body && m_->site_sameframe[i] == 2) m_->site_sameframe[i] = 0;
    }
  }
  mj_setConst(m_, d_);  // subtree masses, inverse weights, actuator_acc0, ... of the changed model
}

void MujocoRobot::applyPush() {
  const double t = d_->time;
  const PushSettings& p = settings_.push;
  const bool on = t >= p.start && t < p.start + p.duration;
  const Eigen::Vector3d f = on ? Eigen::Vector3d(p.impulse / p.duration * p.direction) : Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) d_->xfrc_applied[6 * push_body_ + k] = f[k];
}

MujocoRobot::~MujocoRobot() {
  if (d_) mj_deleteData(d_);
  if (m_) mj_deleteModel(m_);
}

void MujocoRobot::reset() {
  if (key_ >= 0) {
    mj_resetDataKeyframe(m_, d_, key_);
  } else {
    mj_resetData(m_, d_);
  }
  command_.resize(n_);
  tau_applied_.setZero();
  tau_cmd_.setZero();
  rng_.seed(settings_.seed);
  normal_.reset();
  mj_forward(m_, d_);
  head_ = 0;
  sampleMeasurement();
  const RobotState& first = delay_[head_];
  for (auto& s : delay_) {
    if (&s != &first) s = first;  // equal sizes: Eigen copies without allocating
  }
}

void MujocoRobot::read(RobotState& state) const {
  state = delay_[(head_ + 1) % delay_.size()];  // the oldest entry: latency_periods old
}

void MujocoRobot::write(const JointCommand& c) {
  command_.q_ref = c.q_ref;
  command_.qd_ref = c.qd_ref;
  command_.tau_ff = c.tau_ff;
  command_.kp = c.kp;
  command_.kd = c.kd;
}

void MujocoRobot::sampleMeasurement() {
  head_ = (head_ + 1) % delay_.size();
  RobotState& s = delay_[head_];
  s.t = secondsFromNanoseconds(nanosecondsFromSeconds(d_->time));  // the robot clock counts nanoseconds
  const SensorNoise& nz = settings_.noise;
  for (Eigen::Index i = 0; i < n_; ++i) {
    s.q[i] = d_->qpos[qpos_adr_[i]];
    s.qd[i] = d_->qvel[dof_adr_[i]];
    s.tau[i] = tau_applied_[i];
    if (nz.q > 0.0) s.q[i] += nz.q * normal_(rng_);
    if (nz.qd > 0.0) s.qd[i] += nz.qd * normal_(rng_);
    if (nz.tau > 0.0) s.tau[i] += nz.tau * normal_(rng_);
  }
  if (sensor_quat_ >= 0) {
    const mjtNum* w = d_->sensordata + m_->sensor_adr[sensor_quat_];  // MuJoCo order w, x, y, z
    s.imu_quat = Eigen::Quaterniond(w[0], w[1], w[2], w[3]).normalized();
  } else if (base_qpos_ >= 0) {
    const mjtNum* w = d_->qpos + base_qpos_ + 3;
    s.imu_quat = Eigen::Quaterniond(w[0], w[1], w[2], w[3]).normalized();
  }
  if (nz.orientation > 0.0) {
    const Eigen::Vector3d rv(normal_(rng_), normal_(rng_), normal_(rng_));
    const Eigen::Vector3d e = nz.orientation * rv;
    const double angle = e.norm();
    if (angle > 0.0) s.imu_quat = (s.imu_quat * Eigen::Quaterniond(Eigen::AngleAxisd(angle, e / angle))).normalized();
  }
  if (sensor_gyro_ >= 0) {
    const mjtNum* w = d_->sensordata + m_->sensor_adr[sensor_gyro_];
    s.imu_omega = Eigen::Vector3d(w[0], w[1], w[2]);
  }
  if (sensor_acc_ >= 0) {
    const mjtNum* w = d_->sensordata + m_->sensor_adr[sensor_acc_];
    s.imu_acc = Eigen::Vector3d(w[0], w[1], w[2]);
  }
  if (nz.gyro > 0.0) {
    for (int k = 0; k < 3; ++k) s.imu_omega[k] += nz.gyro * normal_(rng_);
  }
  if (nz.acc > 0.0) {
    for (int k = 0; k < 3; ++k) s.imu_acc[k] += nz.acc * normal_(rng_);
  }
}

void MujocoRobot::applyImpedance() {
  for (Eigen::Index i = 0; i < n_; ++i) {
    const double q = d_->qpos[qpos_adr_[i]];
    const double qd = d_->qvel[dof_adr_[i]];
    const double tau = command_.tau_ff[i] + command_.kp[i] * (command_.q_ref[i] - q) +
                       command_.kd[i] * (command_.qd_ref[i] - qd);
    tau_cmd_[i] = tau;
    const double sat = std::clamp(tau, -tau_max_[i], tau_max_[i]);
    tau_applied_[i] = sat;
    d_->ctrl[motor_[i]] = sat / gear_[i];
  }
}

void MujocoRobot::physicsStep() {
  mj_step1(m_, d_);
  applyImpedance();
  if (push_body_ > 0) applyPush();
  mj_step2(m_, d_);
}

void MujocoRobot::controlPeriod(Controller& controller, RobotState& state, JointCommand& command) {
  beginPeriod(state);
  const auto t0 = std::chrono::steady_clock::now();
  controller.tick(state, command);
  last_tick_s_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  endPeriod(command);
}

void MujocoRobot::beginPeriod(RobotState& state) {
  mj_step1(m_, d_);  // positions/velocities and their sensors at this instant
  sampleMeasurement();
  read(state);
}

void MujocoRobot::endPeriod(const JointCommand& command) {
  write(command);
  applyImpedance();
  if (push_body_ > 0) applyPush();
  // The sensors of mj_step2 (the accelerometer: a full post-constraint RNE pass) are read only by the next
  // sample, after the period's last step: with more than one step per period, skip them in this first one.
  const int disable = m_->opt.disableflags;
  if (settings_.control_decimation > 1) m_->opt.disableflags |= mjDSBL_SENSOR;
  mj_step2(m_, d_);
  m_->opt.disableflags = disable;
  for (int k = 1; k < settings_.control_decimation; ++k) physicsStep();
}

double MujocoRobot::time() const { return d_->time; }

Eigen::Vector3d MujocoRobot::basePosition() const {
  if (base_qpos_ < 0) return Eigen::Vector3d::Zero();
  const mjtNum* p = d_->qpos + base_qpos_;
  return Eigen::Vector3d(p[0], p[1], p[2]);
}

Eigen::Quaterniond MujocoRobot::baseOrientation() const {
  if (base_qpos_ < 0) return Eigen::Quaterniond::Identity();
  const mjtNum* p = d_->qpos + base_qpos_ + 3;  // w, x, y, z
  return Eigen::Quaterniond(p[0], p[1], p[2], p[3]).normalized();
}

Eigen::Matrix<double, 6, 1> MujocoRobot::baseVelocity() const {
  Eigen::Matrix<double, 6, 1> v = Eigen::Matrix<double, 6, 1>::Zero();
  if (base_dof_ < 0) return v;
  for (int k = 0; k < 6; ++k) v[k] = d_->qvel[base_dof_ + k];
  return v;
}

void MujocoRobot::jointPositions(Eigen::Ref<Eigen::VectorXd> q) const {
  for (Eigen::Index i = 0; i < n_; ++i) q[i] = d_->qpos[qpos_adr_[i]];
}

void MujocoRobot::jointVelocities(Eigen::Ref<Eigen::VectorXd> qd) const {
  for (Eigen::Index i = 0; i < n_; ++i) qd[i] = d_->qvel[dof_adr_[i]];
}

void MujocoRobot::contactForces(Eigen::Ref<Eigen::Matrix3Xd> w_f) const {
  w_f.setZero();
  const int nb = static_cast<int>(contact_body_ids_.size());
  for (int c = 0; c < d_->ncon; ++c) {
    const mjContact& con = d_->contact[c];
    if (con.efc_address < 0) continue;
    const int b1 = m_->geom_bodyid[con.geom1];
    const int b2 = m_->geom_bodyid[con.geom2];
    int k1 = -1, k2 = -1;
    for (int k = 0; k < nb; ++k) {
      if (contact_body_ids_[k] == b1) k1 = k;
      if (contact_body_ids_[k] == b2) k2 = k;
    }
    if (k1 < 0 && k2 < 0) continue;
    mjtNum f[6];
    mj_contactForce(m_, d_, c, f);  // in the contact frame: normal (from geom1 to geom2), then tangents
    // World force exerted by geom1 on geom2: frame rows are the contact axes.
    Eigen::Vector3d w;
    for (int r = 0; r < 3; ++r) w[r] = con.frame[r] * f[0] + con.frame[3 + r] * f[1] + con.frame[6 + r] * f[2];
    if (k2 >= 0) w_f.col(k2) += w;
    if (k1 >= 0) w_f.col(k1) -= w;
  }
}

}  // namespace centaur::sim
