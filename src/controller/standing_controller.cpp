#include "controller/standing_controller.hpp"

#include <fnmatch.h>

#include <algorithm>
#include <cmath>

#include "common/error.hpp"

namespace centaur {

const char* jointGainsDefaultsYaml() {
  return R"(  gains:                    # joint impedance per group: kp [Nm/rad] in [0, 1e5], kd [Nm s/rad] in [0, 1e3]
    leg: {kp: 1000.0, kd: 10.0}        # hip_yaw, hip_pitch, knee_pitch
    ankle_pitch: {kp: 500.0, kd: 5.0}
    ankle_yaw: {kp: 100.0, kd: 1.0}
    wheel: {kp: 100.0, kd: 2.0}        # j_wheel_* (held at the initial angle)
    torso: {kp: 500.0, kd: 5.0}
    arm: {kp: 300.0, kd: 3.0}          # j_arm*_1 .. j_arm*_4
    wrist: {kp: 50.0, kd: 0.5}         # j_arm*_5 .. j_arm*_7
    other: {kp: 100.0, kd: 1.0}        # any other joint
)";
}

void readJointGains(YamlReader& g, StandingParams& p) {
  if (!p.frames.gain_patterns.empty()) {  // the robot's own groups: each needs its gains, no other key is allowed
    for (const auto& gp : p.frames.gain_patterns) {
      if (!g.has(gp.group)) g.fail(gp.group, "missing: the robot's impedance group needs {kp, kd}");
      JointGains& gains = p.group_gains[gp.group];
      auto c = g.child(gp.group);
      c.get("kp", gains.kp, 0.0, 1e5);
      c.get("kd", gains.kd, 0.0, 1e3);
      c.finish();
    }
    g.finish();
    return;
  }
  for (auto& [name, gains] : std::vector<std::pair<const char*, JointGains*>>{
           {"leg", &p.leg}, {"ankle_pitch", &p.ankle_pitch}, {"ankle_yaw", &p.ankle_yaw}, {"wheel", &p.wheel},
           {"torso", &p.torso}, {"arm", &p.arm}, {"wrist", &p.wrist}, {"other", &p.other}}) {
    auto c = g.child(name);
    c.get("kp", gains->kp, 0.0, 1e5);
    c.get("kd", gains->kd, 0.0, 1e3);
    c.finish();
  }
  g.finish();
}

namespace {
bool contains(const std::string& s, const char* part) { return s.find(part) != std::string::npos; }
}  // namespace

JointGains gainsFor(const std::string& name, const StandingParams& p) {
  for (const auto& gp : p.frames.gain_patterns) {
    for (const auto& pattern : gp.patterns) {
      if (::fnmatch(pattern.c_str(), name.c_str(), 0) == 0) {
        const auto it = p.group_gains.find(gp.group);
        return it == p.group_gains.end() ? JointGains{} : it->second;
      }
    }
  }
  if (!p.frames.gain_patterns.empty()) return JointGains{};  // no group matches: no impedance
  if (contains(name, "hip_yaw") || contains(name, "hip_pitch") || contains(name, "knee_pitch")) return p.leg;
  if (contains(name, "ankle_pitch")) return p.ankle_pitch;
  if (contains(name, "ankle_yaw")) return p.ankle_yaw;
  if (contains(name, "wheel")) return p.wheel;
  if (contains(name, "torso")) return p.torso;
  if (name.rfind("j_arm", 0) == 0 && !name.empty()) {
    const char last = name.back();
    return (last >= '5' && last <= '7') ? p.wrist : p.arm;
  }
  return p.other;
}

const char* StandingParams::defaultsYaml() {
  static const std::string text = std::string(R"(controller:
  feedforward: true         # gravity-compensating torque feed-forward (static wheel forces)
  use_base_estimator: true  # base pose from the BaseEstimator (false: IMU orientation, position 0)
  tangential_weight: 100.0  # [-] cost of tangential vs normal wheel forces in the split, [1, 1e6]
  friction: 0.6             # [-] friction coefficient of the cone projection, [0.05, 5]
  wheel_radius: 0.078       # [m] wheel radius (contact point below the wheel centre), [0.01, 0.5]
)") + jointGainsDefaultsYaml();
  return text.c_str();
}

void StandingParams::read(YamlReader& r) {
  r.get("feedforward", feedforward);
  r.get("use_base_estimator", use_base_estimator);
  r.get("tangential_weight", tangential_weight, 1.0, 1e6);
  r.get("friction", friction, 0.05, 5.0);
  r.get("wheel_radius", wheel_radius, 0.01, 0.5);
  auto g = r.child("gains");
  readJointGains(g, *this);
}

StandingController::StandingController(const std::string& mjcf_path, const StandingParams& params)
    : params_(params), model_(std::make_unique<RobotModel>(mjcf_path)) {
  n_ = model_->numJoints();
  const RobotFrames& frames = params_.frames;
  for (int k = 0; k < 4; ++k) {
    wheel_ids_[k] = model_->frameId(frames.contact_bodies[k]);
    if (wheel_ids_[k] < 0) throw InputError(mjcf_path + ": frame '" + frames.contact_bodies[k] + "' not found");
  }
  const int imu = model_->frameId(frames.imu);
  const int base = model_->frameId(frames.base);
  if (imu < 0 || base < 0) {
    throw InputError(mjcf_path + ": frames '" + frames.imu + "' and '" + frames.base + "' are required");
  }
  q_model_.setZero(model_->nq());
  v_model_.setZero(model_->nv());
  g_.setZero(model_->nv());
  for (auto& J : J_) J.setZero(3, model_->nv());
  // imu_R_base from the model at the home posture (the IMU is rigidly attached to the pelvis).
  q_home_ = model_->homeJoints();
  q_model_[3] = 1.0;
  q_model_.tail(n_) = q_home_;
  model_->update(q_model_, v_model_);
  const Eigen::Quaterniond w_q_base(model_->framePose(base).rotation());
  const Eigen::Quaterniond w_q_imu(model_->framePose(imu).rotation());
  imu_q_base_ = (w_q_imu.conjugate() * w_q_base).normalized();
  kp_.setZero(n_);
  kd_.setZero(n_);
  good_tau_ff_.setZero(n_);
  const auto& names = model_->jointNames();
  for (int i = 0; i < n_; ++i) {
    const JointGains g = gainsFor(names[static_cast<std::size_t>(i)], params_);
    kp_[i] = g.kp;
    kd_[i] = g.kd;
  }
  kd_safe_ = 3.0 * kd_;  // as the whole-body controller's default safe_kd_scale
  if (params_.use_base_estimator) {
    BaseEstimatorParams ep;
    ep.wheel_radius = params_.wheel_radius;
    ep.wheel_bodies = frames.contact_bodies;
    ep.wheel_centres = frames.foot_centres;
    estimator_.init(model_->description(), ep);
  }
  for (int k = 0; k < 4; ++k) {
    w_inv_.segment<3>(3 * k) << 1.0 / params_.tangential_weight, 1.0 / params_.tangential_weight, 1.0;
  }
}

StandingController::~StandingController() = default;

void StandingController::start(const RobotState& state, JointCommand& command) {
  if (state.q.size() != n_) {
    throw InputError("standing controller: the robot has " + std::to_string(state.q.size()) +
                     " joints, the model " + std::to_string(n_));
  }
  command.resize(n_);
  // Wheels (continuous) hold their initial angle; everything else goes to home.
  const auto& names = model_->jointNames();
  const auto& wheels = params_.frames.wheel_joints;
  for (int i = 0; i < n_; ++i) {
    const std::string& name = names[static_cast<std::size_t>(i)];
    const bool wheel = wheels.empty() ? contains(name, "wheel") : std::find(wheels.begin(), wheels.end(), name) != wheels.end();
    if (wheel) q_home_[i] = state.q[i];
  }
  tick(state, command);
}

void StandingController::computeFeedforward(const RobotState& state, JointCommand& command) noexcept {
  // Base pose (only its orientation matters for gravity and the base rows of the contact Jacobians);
  // static: v = 0.
  if (params_.use_base_estimator) {
    static constexpr bool kAllStance[BaseEstimator::kWheels] = {true, true, true, true};
    estimator_.update(state, kAllStance);
    q_model_ = estimator_.q();
  } else {
    const Eigen::Quaterniond w_q_base = (state.imu_quat * imu_q_base_).normalized();
    q_model_.head<3>().setZero();
    q_model_[3] = w_q_base.w();
    q_model_[4] = w_q_base.x();
    q_model_[5] = w_q_base.y();
    q_model_[6] = w_q_base.z();
    q_model_.tail(n_) = state.q;
  }
  model_->update(q_model_, v_model_);
  model_->gravityForces(g_);
  for (int k = 0; k < 4; ++k) {
    const Eigen::Isometry3d w_T_wheel = model_->framePose(wheel_ids_[k]);
    const Eigen::Vector3d w_centre = w_T_wheel * params_.frames.centre_offsets[k];  // the origin for a zero offset
    const Eigen::Vector3d w_contact = w_centre - params_.wheel_radius * Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d f_contact = w_T_wheel.inverse() * w_contact;
    model_->pointJacobian(wheel_ids_[k], f_contact, J_[k]);
    A_.block<6, 3>(0, 3 * k) = J_[k].leftCols<6>().transpose();
  }
  // Weighted least norm: F = W^-1 A^T (A W^-1 A^T)^-1 g_b.
  AWA_.noalias() = A_ * w_inv_.asDiagonal() * A_.transpose();
  ldlt_.compute(AWA_);
  const Eigen::Matrix<double, 6, 1> lambda = ldlt_.solve(g_.head<6>());
  F_.noalias() = w_inv_.asDiagonal() * (A_.transpose() * lambda);
  command.tau_ff = g_.tail(n_);
  for (int k = 0; k < 4; ++k) {
    Eigen::Vector3d f = F_.segment<3>(3 * k);
    f.z() = std::max(f.z(), 0.0);
    const double ft = f.head<2>().norm();
    const double ft_max = params_.friction * f.z();
    if (ft > ft_max && ft > 0.0) f.head<2>() *= ft_max / ft;
    forces_.col(k) = f;
    command.tau_ff.noalias() -= J_[k].rightCols(n_).transpose() * f;
  }
}

void StandingController::tick(const RobotState& state, JointCommand& command) noexcept {
  const bool finite = state.q.allFinite() && state.qd.allFinite() && state.tau.allFinite() &&
                      state.imu_quat.coeffs().allFinite() && state.imu_omega.allFinite() && state.imu_acc.allFinite();
  if (!finite && !safe_) {
    safe_ = true;
    safe_reason_ = "invalid_input";
  }
  if (safe_requested_ && !safe_) {
    safe_ = true;
    safe_reason_ = "requested";
  }
  if (safe_ && resume_pending_ && finite && !safe_requested_) {
    safe_ = false;
    safe_reason_ = "";
  }
  if (!safe_) resume_pending_ = false;  // a resume waits for a valid measurement
  command.q_ref = q_home_;
  command.qd_ref.setZero();
  command.kp = kp_;
  if (safe_) {
    command.kd = kd_safe_;
    command.tau_ff = good_tau_ff_;
    return;
  }
  command.kd = kd_;
  if (params_.feedforward) {
    computeFeedforward(state, command);
  } else {
    command.tau_ff.setZero();
  }
  if (command.tau_ff.allFinite()) good_tau_ff_ = command.tau_ff;
}

void StandingController::requestSafeMode() noexcept {
  safe_requested_ = true;
  resume_pending_ = false;
}

void StandingController::resume() noexcept {
  safe_requested_ = false;
  resume_pending_ = true;
}

ControllerReport StandingController::report() const noexcept {
  ControllerReport r;
  r.phase = "standing";
  r.safe_mode = safe_;
  r.safe_reason = safe_reason_;
  r.stance = {true, true, true, true};
  return r;
}

}  // namespace centaur
