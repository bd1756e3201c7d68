#include "controller/whole_body_controller.hpp"

#include <chrono>
#include <cmath>

#include "common/error.hpp"
#include "common/yaml_reader.hpp"
#include "controller/robot_tasks.hpp"
#include "controller/task_angular_momentum.hpp"
#include "controller/task_cartesian.hpp"
#include "controller/task_com.hpp"
#include "controller/task_pelvis_angular_velocity.hpp"
#include "controller/task_postural.hpp"

namespace centaur {

const char* toString(WholeBodyStatus status) {
  switch (status) {
    case WholeBodyStatus::kNotStarted: return "not_started";
    case WholeBodyStatus::kOk: return "ok";
    case WholeBodyStatus::kSafeInvalidInput: return "safe_invalid_input";
    case WholeBodyStatus::kSafeQpFailed: return "safe_qp_failed";
    case WholeBodyStatus::kSafeRequested: return "safe_requested";
  }
  return "unknown";
}

namespace {
bool contains(const std::string& s, const char* part) { return s.find(part) != std::string::npos; }

template <class T>
std::shared_ptr<T> findTask(const LoadedStack& s, const std::string& name) {
  auto it = s.tasks.find(name);
  return it == s.tasks.end() ? nullptr : std::dynamic_pointer_cast<T>(it->second);
}
}  // namespace

WholeBodyController::WholeBodyController(const std::string& mjcf_path, const WholeBodyParams& params)
    : params_(params),
      model_meas_(std::make_unique<RobotModel>(mjcf_path)),  // the one parse; the other models are workspaces on it
      model_ik_(std::make_unique<RobotModel>(model_meas_->description())) {
  if (!(params_.dt > 0.0 && params_.dt <= 0.01)) throw InputError("whole-body controller: dt must be in (0, 0.01] s");
  if (!(params_.safe_kd_scale >= 1.0 && params_.safe_kd_scale <= 100.0))
    throw InputError("whole-body controller: safe_kd_scale must be in [1, 100]");
  if (params_.stack_file.empty() && params_.stack_yaml.empty())
    throw InputError("whole-body controller: stack_file or stack_yaml is required");
  n_ = model_meas_->numJoints();
  nq_ = model_meas_->nq();
  nv_ = model_meas_->nv();
  const RobotFrames& f = params_.frames;
  params_.estimator.wheel_bodies = params_.detector.wheel_bodies = params_.force.wheel_bodies = f.contact_bodies;
  params_.estimator.wheel_centres = params_.detector.wheel_centres = params_.force.wheel_centres = f.foot_centres;
  params_.estimator.wheel_radius = params_.detector.wheel_radius = params_.force.wheel_radius = f.foot_radius[0];
  params_.detector.leg_joints = f.leg_joints;
  estimator_.init(model_meas_->description(), params_.estimator);
  detector_.init(*model_meas_, params_.detector);
  force_.init(*model_meas_, params_.force);
  registerRobotTasks(registry_, *model_ik_, params_.dt);
  if (!params_.stack_file.empty()) {
    stack_ = loadStack(loadYamlFile(params_.stack_file), params_.stack_file, registry_);
  } else {
    stack_ = loadStack(loadYamlString(params_.stack_yaml, "<stack>"), "<stack>", registry_);
  }
  hqp_.configure(stack_.stack, nv_);
  for (int k = 0; k < 4; ++k) feet_[k] = findTask<CartesianTask>(stack_, params_.foot_tasks[k]);
  posture_ = findTask<PosturalTask>(stack_, params_.posture_task);
  pelvis_ = findTask<PelvisAngularVelocityTask>(stack_, params_.pelvis_task);
  momentum_ = findTask<AngularMomentumTask>(stack_, params_.momentum_task);
  // The IK model computes the centroidal momentum matrix only if a task of the stack needs it.
  ik_detail_ = RobotModel::Detail::kJacobians;
  for (const auto& named : stack_.tasks) {
    if (std::dynamic_pointer_cast<AngularMomentumTask>(named.second) || std::dynamic_pointer_cast<ComTask>(named.second))
      ik_detail_ = RobotModel::Detail::kMomentum;
  }

  kp_.setZero(n_);
  kd_.setZero(n_);
  const auto& names = model_meas_->jointNames();
  for (int i = 0; i < n_; ++i) {
    const JointGains g = gainsFor(names[static_cast<std::size_t>(i)], params_.impedance);
    kp_[i] = g.kp;
    kd_[i] = g.kd;
  }
  kd_safe_ = params_.safe_kd_scale * kd_;
  tau_max_ = model_meas_->limits().tau_max;
  for (int i = 0; i < n_; ++i) {
    if (!(tau_max_[i] > 0.0) || !std::isfinite(tau_max_[i])) tau_max_[i] = 1e9;
  }
  q_home_ = model_meas_->homeJoints();
  q_ref_.setZero(n_);
  qd_ref_.setZero(n_);
  x_.setZero(nv_);
  q_ik_.setZero(nq_);
  v_ik_.setZero(nv_);
  vdot_d_.setZero(nv_);
  good_q_ref_.setZero(n_);
  good_tau_ff_.setZero(n_);
}

WholeBodyController::~WholeBodyController() = default;

bool WholeBodyController::finiteInput(const RobotState& s) const noexcept {
  return std::isfinite(s.t) && s.q.size() == n_ && s.qd.size() == n_ && s.tau.size() == n_ && s.q.allFinite() &&
         s.qd.allFinite() && s.tau.allFinite() && s.imu_quat.coeffs().allFinite() && s.imu_omega.allFinite() &&
         s.imu_acc.allFinite() && s.imu_quat.norm() > 0.5;
}

void WholeBodyController::start(const RobotState& state, JointCommand& command) {
  if (state.q.size() != n_) {
    throw InputError("whole-body controller: the robot has " + std::to_string(state.q.size()) + " joints, the model " +
                     std::to_string(n_));
  }
  if (!finiteInput(state)) throw InputError("whole-body controller: the first measurement is not finite");
  command.resize(n_);
  const auto& names = model_meas_->jointNames();
  for (int i = 0; i < n_; ++i) {
    if (contains(names[static_cast<std::size_t>(i)], "wheel")) q_home_[i] = state.q[i];  // wheels keep their angle
  }
  detector_.reset();
  contacts_ = WheelContacts{};
  q_ref_ = state.q;
  qd_ref_.setZero();
  counters_ = WholeBodyCounters{};
  // First estimate and model updates, then hold the feet where they are.
  const bool all[4] = {true, true, true, true};
  estimator_.update(state, all);
  model_meas_->update(estimator_.q(), estimator_.v());
  q_ik_ = estimator_.q();
  v_ik_.setZero();
  model_ik_->update(q_ik_, v_ik_, RobotModel::Detail::kMomentum);  // velocity IK: no dynamics needed
  holdCurrentReferences();
  if (posture_) posture_->setReference(q_home_);
  // gravity compensation of the start posture as the first "last good" feed-forward
  const bool ok_fd = force_.compute(*model_meas_, vdot_d_, F_d_, contacts_) != ForceDistributionStatus::kFailed;
  good_tau_ff_ = ok_fd ? force_.tauFeedforward() : Eigen::VectorXd::Zero(n_);
  good_q_ref_ = q_ref_;
  status_ = WholeBodyStatus::kOk;
  resume_pending_ = false;
  tick(state, command);
}

void WholeBodyController::holdCurrentReferences() noexcept {
  for (auto& f : feet_) {
    if (f) f->holdCurrent();
  }
  for (auto& [name, task] : stack_.tasks) {
    (void)name;
    if (auto* c = dynamic_cast<CartesianTask*>(task.get())) c->holdCurrent();
    if (auto* c = dynamic_cast<ComTask*>(task.get())) c->holdCurrent();
  }
}

void WholeBodyController::setFootReferences(const Eigen::Matrix<double, 3, 4>& b_p_wheel,
                                            const Eigen::Matrix<double, 3, 4>& b_v_wheel) {
  for (int k = 0; k < 4; ++k) {
    if (!feet_[k]) continue;
    feet_[k]->setReference(b_p_wheel.col(k));
    Eigen::Matrix<double, 6, 1> v = Eigen::Matrix<double, 6, 1>::Zero();
    v.head<3>() = b_v_wheel.col(k);
    feet_[k]->setVelocityReference(v);
  }
}

void WholeBodyController::setPlannedForces(const Forces& F_d, bool use_default) {
  F_d_ = F_d;
  default_forces_ = use_default;
}

void WholeBodyController::setPostureReference(const Eigen::Ref<const Eigen::VectorXd>& q_d) {
  if (posture_) posture_->setReference(q_d);
}

void WholeBodyController::setPostureVelocity(const Eigen::Ref<const Eigen::VectorXd>& qd_d) {
  if (posture_) posture_->setVelocityReference(qd_d);
}

void WholeBodyController::setPelvisAngularVelocity(const Eigen::Vector3d& w_omega_d) {
  if (pelvis_) pelvis_->setReference(w_omega_d);
}

void WholeBodyController::setAngularMomentum(const Eigen::Vector3d& h_ang_d) {
  if (momentum_) momentum_->setReference(h_ang_d);
}

void WholeBodyController::setReferences(const WholeBodyReferences& r) noexcept {
  if ((r.set & WholeBodyReferences::kPosture) && posture_) posture_->setReference(r.q_posture);
  if ((r.set & WholeBodyReferences::kPostureVelocity) && posture_) posture_->setVelocityReference(r.qd_posture);
  if ((r.set & WholeBodyReferences::kPelvisAngularVelocity) && pelvis_) pelvis_->setReference(r.w_omega_pelvis);
  if ((r.set & WholeBodyReferences::kAngularMomentum) && momentum_) momentum_->setReference(r.h_angular);
}

void WholeBodyController::requireTasks(unsigned mask, const std::string& who) const {
  auto need = [&](unsigned bit, const void* task, const std::string& name, const char* what) {
    if ((mask & bit) && !task) {
      throw InputError(who + " sets the " + what + ", but its stack has no task '" + name + "' of that kind");
    }
  };
  need(WholeBodyReferences::kPosture, posture_.get(), params_.posture_task, "posture reference");
  need(WholeBodyReferences::kPostureVelocity, posture_.get(), params_.posture_task, "posture velocity");
  need(WholeBodyReferences::kPelvisAngularVelocity, pelvis_.get(), params_.pelvis_task, "pelvis angular velocity");
  need(WholeBodyReferences::kAngularMomentum, momentum_.get(), params_.momentum_task, "angular momentum");
}

void WholeBodyController::setContactNormals(const std::array<Eigen::Vector3d, 4>& w_normal) noexcept {
  for (int k = 0; k < 4; ++k) {
    if (!w_normal[k].allFinite() || w_normal[k].norm() < 0.5) continue;
    contacts_.normal[k] = w_normal[k].normalized();
    detector_.setNormal(k, contacts_.normal[k]);
  }
}

void WholeBodyController::writeSafe(JointCommand& command) noexcept {
  command.q_ref = good_q_ref_;
  command.qd_ref.setZero();
  command.tau_ff = good_tau_ff_;
  command.kp = kp_;
  command.kd = kd_safe_;
}

void WholeBodyController::enterSafe(WholeBodyStatus why, JointCommand& command) noexcept {
  if (!inSafeMode()) status_ = why;
  ++counters_.safe_ticks;
  writeSafe(command);
}

// 2-3. The estimate, the measured model at it and contact detection; false when the estimate is not finite.
bool WholeBodyController::estimate(const RobotState& state) noexcept {
  bool stance[4];
  for (int k = 0; k < 4; ++k) stance[k] = contacts_.stance[k];
  // the estimate, and the measured model at it: M, bias forces, Jacobians
  estimator_.update(state, stance, *model_meas_, RobotModel::Detail::kDynamics);
  if (!estimator_.q().allFinite() || !estimator_.v().allFinite()) return false;
  if (params_.use_contact_detector && detector_.update(*model_meas_, state.tau, params_.dt)) {
    contacts_.stance = detector_.inContact();
  } else if (!params_.use_contact_detector) {
    contacts_.stance = {true, true, true, true};
  }
  for (int k = 0; k < 4; ++k) contacts_.stance[k] = contacts_.stance[k] && stance_mask_[k];
  return true;
}

// 7. Force distribution on the measured state. A failed distribution keeps the last good feed-forward.
void WholeBodyController::distributeForces() noexcept {
  if (default_forces_) {
    int ns = 0;
    for (bool s : contacts_.stance) ns += s ? 1 : 0;
    F_d_.setZero();
    if (ns > 0) {
      const double fz = -model_meas_->totalMass() * model_meas_->gravity().z() / ns;
      for (int k = 0; k < 4; ++k) F_d_(2, k) = contacts_.stance[k] ? fz : 0.0;
    }
  }
  const ForceDistributionStatus fs = force_.compute(*model_meas_, vdot_d_, F_d_, contacts_);
  if (fs == ForceDistributionStatus::kFailed || !force_.tauFeedforward().allFinite()) {
    ++counters_.force_failures;
  } else {
    if (fs == ForceDistributionStatus::kRelaxed) ++counters_.force_relaxed;
    // never command a feed-forward beyond the effort limits (the drive would saturate it anyway)
    good_tau_ff_ = force_.tauFeedforward().cwiseMax(-tau_max_).cwiseMin(tau_max_);
  }
}

void WholeBodyController::tick(const RobotState& state, JointCommand& command) noexcept {
  ++counters_.ticks;
  if (status_ == WholeBodyStatus::kNotStarted) return;
  if (!finiteInput(state)) {
    ++counters_.invalid_inputs;
    enterSafe(WholeBodyStatus::kSafeInvalidInput, command);
    return;
  }
  if (safe_requested_) {
    enterSafe(WholeBodyStatus::kSafeRequested, command);
    return;
  }
  if (inSafeMode() && !resume_pending_) {
    enterSafe(status_, command);
    return;
  }
  // 2-3. estimate, measured model, contact detection
  if (!estimate(state)) {
    ++counters_.invalid_inputs;
    enterSafe(WholeBodyStatus::kSafeInvalidInput, command);
    return;
  }
  if (resume_pending_) {  // leave safe mode: restart the IK from the measured posture
    q_ref_ = state.q;
    qd_ref_.setZero();
  }
  // 4. IK model at [estimated base, q_ref]
  q_ik_.head<7>() = estimator_.q().head<7>();
  q_ik_.tail(n_) = q_ref_;
  v_ik_.head<6>() = estimator_.v().head<6>();
  v_ik_.tail(n_) = qd_ref_;
  model_ik_->update(q_ik_, v_ik_, ik_detail_);  // velocity IK: no dynamics needed
  if (resume_pending_) {
    holdCurrentReferences();
    resume_pending_ = false;
    status_ = WholeBodyStatus::kOk;
  }
  // 5. HQP
  const auto t0 = std::chrono::steady_clock::now();
  hqp_.update();
  qp_status_ = hqp_.solve(x_);
  qp_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (qp_status_ != QpStatus::kOptimal || !x_.allFinite()) {
    ++counters_.qp_failures;
    enterSafe(WholeBodyStatus::kSafeQpFailed, command);
    return;
  }
  // 6. integrate
  qd_ref_ = x_.tail(n_);
  q_ref_ += params_.dt * qd_ref_;
  // 7. force distribution
  distributeForces();
  // 8. command
  good_q_ref_ = q_ref_;
  command.q_ref = q_ref_;
  command.qd_ref = qd_ref_;
  command.tau_ff = good_tau_ff_;
  command.kp = kp_;
  command.kd = kd_;
  status_ = WholeBodyStatus::kOk;
}

}  // namespace centaur
