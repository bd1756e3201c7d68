#include "stabilizers/ocp_posture_stabilizer.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"
#include "common/yaml_reader.hpp"
#include "controller/whole_body_controller.hpp"
#include "data/arm_trajectory_io.hpp"
#include "stabilizers/stabilizer_stacks.hpp"

namespace centaur {

const char* OcpPostureParams::defaultsYaml() {
  return R"(ocp:                          # OCP postural task, stabilizer 3 (docs/stabilizers.md)
  flywheel_file: ""              # HDF5 from `centaur plan arm-flywheel`; "" = the caller's plan (simulate: planned now)
  flywheel_group: arm-flywheel   # group in that file
  gamma_tau: 1.0                 # [1/rad] phase per radian of pitch: d tau/dt = gamma_tau omega_y, [0, 100]
  max_speed: 1.0                 # |d tau/dt| <= max_speed / period (1 = the planned speed), [0, 10]
  initial_phase: 0.2             # tau_0, [0, 1): where the arms wait on the plan (chosen in the jump scenarios)
  blend_time: 1.0                # [s] home -> q*(tau_0) after start, [0, 10]
  arms: both                     # both | left | right (right = mirror image of the plan)
  interpolation: samples         # samples (1 kHz rows) | knots (the OCP nodes, as the paper)
  after_end: home                # arms after the primitive: home | initial (q*(tau_0)) | hold, blended
  velocity_feedforward: false    # also feed d q*/d tau * d tau/dt to the posture task (docs/jumps.md)
)";
}

void OcpPostureParams::read(YamlReader& r) {
  r.get("flywheel_file", flywheel_file);
  r.get("flywheel_group", flywheel_group);
  r.get("gamma_tau", gamma_tau, 0.0, 100.0);
  r.get("max_speed", max_speed, 0.0, 10.0);
  r.get("initial_phase", initial_phase, 0.0, 1.0);
  if (initial_phase >= 1.0) r.fail("initial_phase", "must be in [0, 1)");
  r.get("blend_time", blend_time, 0.0, 10.0);
  r.get("arms", arms, {"both", "left", "right"});
  r.get("interpolation", interpolation, {"samples", "knots"});
  r.get("after_end", after_end, {"home", "initial", "hold"});
  r.get("velocity_feedforward", velocity_feedforward);
  if (flywheel_group.empty()) r.fail("flywheel_group", "must not be empty");
}

void interpolatePeriodic(const data::RowMatrix& table, double tau, Eigen::Ref<Eigen::VectorXd> out) noexcept {
  const Eigen::Index M = table.rows() - 1;
  if (M < 1 || !std::isfinite(tau)) {
    out = table.row(0).transpose();
    return;
  }
  tau -= std::floor(tau);
  const double x = tau * static_cast<double>(M);
  const Eigen::Index k = std::min<Eigen::Index>(M - 1, static_cast<Eigen::Index>(std::floor(x)));
  const double f = x - static_cast<double>(k);
  for (Eigen::Index j = 0; j < table.cols(); ++j) out[j] = table(k, j) + f * (table(k + 1, j) - table(k, j));
}

namespace {
std::shared_ptr<const data::ArmTrajectory> loadTrajectory(const OcpPostureParams& p) {
  if (p.flywheel_file.empty()) {
    throw InputError("ocp stabilizer: key 'ocp.flywheel_file' is empty: the OCP postural task needs an arm-flywheel "
                     "plan (`centaur plan arm-flywheel --out F.h5`, then --flywheel F.h5)");
  }
  auto tr = std::make_shared<data::ArmTrajectory>(data::readArmTrajectory(p.flywheel_file, p.flywheel_group));
  if (!tr->solve.solved()) {
    throw InputError(p.flywheel_file, p.flywheel_group,
                     "the arm trajectory is flagged '" + tr->solve.status + "' (not converged); re-plan it");
  }
  return tr;
}
}  // namespace

OcpPostureStabilizer::OcpPostureStabilizer(OcpPostureParams params)
    : params_(std::move(params)), traj_(loadTrajectory(params_)) {
  init();
}

OcpPostureStabilizer::OcpPostureStabilizer(OcpPostureParams params,
                                           std::shared_ptr<const data::ArmTrajectory> trajectory)
    : params_(std::move(params)), traj_(std::move(trajectory)) {
  if (!traj_) throw InputError("ocp stabilizer: no arm trajectory");
  init();
}

void OcpPostureStabilizer::init() {
  const data::ArmTrajectory& tr = *traj_;
  const std::string where = params_.flywheel_file.empty() ? std::string("<arm-flywheel plan in memory>") : params_.flywheel_file;
  if (tr.q.cols() != 7 || tr.q.rows() < 2 || tr.joint_names.size() != 7 || !(tr.period > 0.0)) {
    throw InputError(where + ": the arm trajectory needs 7 joints, >= 2 samples and a positive period");
  }
  if (params_.interpolation == "knots") {
    if (tr.knot_x.rows() < 2 || tr.knot_x.cols() != 14) throw InputError(where + ": the trajectory has no knots");
    table_ = tr.knot_x.leftCols(7);
  } else {
    table_ = tr.q;
  }
  if ((table_.row(0) - table_.row(table_.rows() - 1)).cwiseAbs().maxCoeff() > 1e-4) {
    throw InputError(where + ": the arm trajectory is not periodic (first and last rows differ by more than 1e-4 rad)");
  }
  const double h_mean = tr.h_ang.rows() == tr.q.rows() ? tr.h_ang.col(1).mean() : 1.0;
  direction_ = h_mean >= 0.0 ? 1.0 : -1.0;
  after_end_ = params_.after_end == "initial" ? AfterEnd::kInitial
               : params_.after_end == "hold"  ? AfterEnd::kHold
                                              : AfterEnd::kHome;
  mirror_ = data::armMirrorSigns();
  tau_ = params_.initial_phase;
  q_arm_.setZero(7);
}

std::string OcpPostureStabilizer::stackYaml(const RobotFrames& frames) const { return postureStackYaml(frames); }

void OcpPostureStabilizer::start(const std::vector<std::string>& names, const Eigen::VectorXd& q_home) {
  auto find = [&](const std::string& j) {
    auto it = std::find(names.begin(), names.end(), j);
    if (it == names.end()) throw InputError("ocp stabilizer: the robot has no joint '" + j + "' (arm of the plan)");
    return static_cast<int>(it - names.begin());
  };
  left_.assign(7, -1);
  right_.assign(7, -1);
  for (int j = 0; j < 7; ++j) {
    const std::string& l = traj_->joint_names[j];
    std::string r = l;
    const auto pos = r.find("arm1");
    if (pos == std::string::npos) throw InputError("ocp stabilizer: plan joint '" + l + "' is not a left-arm joint (j_arm1_*)");
    r.replace(pos, 4, "arm2");
    if (params_.arms != "right") left_[j] = find(l);
    if (params_.arms != "left") right_[j] = find(r);
  }
  if (q_home.size() != static_cast<Eigen::Index>(names.size())) {
    throw InputError("ocp stabilizer: q_home has " + std::to_string(q_home.size()) + " entries for " +
                     std::to_string(names.size()) + " joints");
  }
  q_home_ = q_home;
  q_d_ = q_home;
  qd_d_.setZero(q_home.size());
  q_from_ = q_home;
  q_arm_.setZero(7);
  tau_ = params_.initial_phase;
  elapsed_ = 0.0;
  was_active_ = ended_ = false;
}

void OcpPostureStabilizer::step(const RobotState& state, double dt, bool active) noexcept {
  if (q_d_.size() == 0) return;  // not started
  if (active != was_active_) {
    if (!active || ended_) {  // the primitive ended, or starts again after an end: blend from here
      q_from_ = q_d_;
      elapsed_ = 0.0;
    }
    ended_ = !active;
    was_active_ = active;
  }
  const bool dt_ok = std::isfinite(dt) && dt > 0.0;
  if (dt_ok) elapsed_ += dt;
  const double w = state.imu_omega.y();
  double rate = 0.0;
  if (active && dt_ok && std::isfinite(w)) {
    const double rmax = params_.max_speed / traj_->period;
    rate = std::clamp(direction_ * params_.gamma_tau * w, -rmax, rmax);
    tau_ += rate * dt;
    tau_ -= std::floor(tau_);  // periodic plan: wrap into [0, 1)
  }
  const bool home = ended_ && after_end_ == AfterEnd::kHome;
  interpolatePeriodic(table_, ended_ && after_end_ == AfterEnd::kInitial ? params_.initial_phase : tau_, q_arm_);
  double s = 1.0;
  if (params_.blend_time > 0.0) {
    const double x = std::min(1.0, elapsed_ / params_.blend_time);
    s = x * x * (3.0 - 2.0 * x);
  }
  // slope of the interpolated segment (d q*/d tau), for the velocity feed-forward while replaying
  const long M = table_.rows() - 1;
  const long k = std::clamp(static_cast<long>(std::floor(tau_ * M)), 0L, M - 1);
  const bool replaying = active && !ended_ && s >= 1.0;
  for (int j = 0; j < 7; ++j) {
    const double qd_arm = replaying ? rate * M * (table_(k + 1, j) - table_(k, j)) : 0.0;
    if (left_[j] >= 0) {
      const int i = left_[j];
      q_d_[i] = (1.0 - s) * q_from_[i] + s * (home ? q_home_[i] : q_arm_[j]);
      qd_d_[i] = qd_arm;
    }
    if (right_[j] >= 0) {
      const int i = right_[j];
      q_d_[i] = (1.0 - s) * q_from_[i] + s * (home ? q_home_[i] : mirror_[j] * q_arm_[j]);
      qd_d_[i] = mirror_[j] * qd_arm;
    }
  }
}

unsigned OcpPostureStabilizer::references() const {
  return WholeBodyReferences::kPosture | (params_.velocity_feedforward ? WholeBodyReferences::kPostureVelocity : 0u);
}

void OcpPostureStabilizer::update(const RobotState& state, double dt, bool active, WholeBodyReferences& out) noexcept {
  step(state, dt, active);
  out.set = 0;
  if (q_d_.size() == 0) return;
  out.q_posture = q_d_;
  out.qd_posture = qd_d_;
  out.set = references();
}

}  // namespace centaur
