#include "stabilizers/jump_controller.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/error.hpp"
#include "common/yaml_reader.hpp"

namespace centaur {

std::string JumpControllerParams::defaultsYaml() {
  return R"(controller:
  settle_time: 0.5          # [s] hold the first sample before the primitive starts, [0, 10]
  start: settle             # settle: the primitive starts settle_time after start | trigger: on a trigger, not earlier
  early_touchdown: 0.08     # [s] contact accepted this long before a planned touch-down, [0, 1]
  touchdown_search_speed: 0.3  # [m/s] late touch-down: the wheel moves on along -n (0: off), [0, 5]
  touchdown_search_max: 0.15   # [m] largest search offset, [0, 0.5]
  recover_time: 0.0         # [s] after the primitive, back to its first pose in this time (0: hold the end), [0, 10]
  feedforward_acceleration: true  # planned base acceleration into the force distribution
  friction: 0.5             # [-] mu of the force distribution's pyramid, [0.01, 5]
  contact_on: 60.0          # [N] contact detector: touch-down threshold, (off, 1e4]
  contact_off: 30.0         # [N] contact detector: lift-off threshold, [0, on)
)" + std::string(jointGainsDefaultsYaml());
}

void JumpControllerParams::read(YamlReader& r) {
  r.get("settle_time", settle_time, 0.0, 10.0);
  r.get("start", start, {"settle", "trigger"});
  r.get("early_touchdown", early_touchdown, 0.0, 1.0);
  r.get("recover_time", recover_time, 0.0, 10.0);
  r.get("touchdown_search_speed", touchdown_search_speed, 0.0, 5.0);
  r.get("touchdown_search_max", touchdown_search_max, 0.0, 0.5);
  r.get("feedforward_acceleration", feedforward_acceleration);
  r.get("friction", wbc.force.friction, 0.01, 5.0);
  r.get("contact_on", wbc.detector.on_threshold, 0.0, 1e4);
  r.get("contact_off", wbc.detector.off_threshold, 0.0, 1e4);
  if (!(wbc.detector.off_threshold < wbc.detector.on_threshold)) r.fail("contact_off", "must be below contact_on");
  auto g = r.child("gains");
  readJointGains(g, wbc.impedance);
}

JumpController::JumpController(const std::string& mjcf_path, const data::Primitive& primitive,
                               std::unique_ptr<Stabilizer> stabilizer, const JumpControllerParams& params)
    : params_(params), replay_(primitive), stabilizer_(std::move(stabilizer)) {
  if (!stabilizer_) throw InputError("jump controller: no stabilizer");
  params_.wbc.stack_file.clear();
  params_.wbc.stack_yaml = stabilizer_->stackYaml(params_.wbc.frames);
  wbc_ = std::make_unique<WholeBodyController>(mjcf_path, params_.wbc);
  wbc_->requireTasks(stabilizer_->references(), std::string("stabilizer '") + stabilizer_->name() + "'");
  refs_.resize(wbc_->ikModel().numJoints());
  vdot_.setZero(wbc_->ikModel().nv());
  replay_.sample(0.0, first_);
  replay_.sample(replay_.duration(), last_);
  use_trigger_ = params_.start == "trigger";
}

void JumpController::start(const RobotState& state, JointCommand& command) {
  t0_ = state.t;
  triggered_ = false;
  t_rel_ = -params_.settle_time;
  replay_.sample(t_rel_, sample_);
  w_search_.setZero();
  w_search_end_.setZero();
  end_latched_ = false;
  // The whole-body controller's start() holds the feet where they are (= the first sample's r_C) and writes
  // the first command; the replay and the stabilizer take over from the next tick.
  wbc_->start(state, command);
  stabilizer_->start(wbc_->ikModel().jointNames(), wbc_->homePosture());
}

double JumpController::primitiveStart() const {
  if (use_trigger_ && !triggered_) return std::numeric_limits<double>::infinity();
  return use_trigger_ ? std::max(t_trigger_, t0_ + params_.settle_time) : t0_ + params_.settle_time;
}

void JumpController::triggerStart(double t) noexcept {
  if (triggered_ || !std::isfinite(t)) return;
  triggered_ = true;
  t_trigger_ = t;
}

ControllerReport JumpController::report() const noexcept {
  ControllerReport r;
  const bool waiting = use_trigger_ && !triggered_;
  r.phase = waiting                                          ? "waiting"
            : t_rel_ < 0.0                                   ? "settle"
            : t_rel_ < replay_.duration()                    ? "primitive"
            : params_.recover_time > 0.0 &&
                      t_rel_ < replay_.duration() + params_.recover_time ? "recover"
                                                             : "end";
  r.safe_mode = wbc_->inSafeMode();
  r.safe_reason = r.safe_mode ? toString(wbc_->status()) : "";
  r.stance = wbc_->stance();
  return r;
}

void JumpController::tick(const RobotState& state, JointCommand& command) noexcept {
  // Time since the primitive's start: after settle_time; with a trigger, not before it (held until then).
  t_rel_ = state.t - t0_ - params_.settle_time;
  if (use_trigger_) t_rel_ = triggered_ ? std::min(t_rel_, state.t - t_trigger_) : -1e9;
  replay_.sample(t_rel_, sample_);
  const double t_after = t_rel_ - replay_.duration();
  const double dt = wbc_->params().dt;
  // late touch-down search (W offsets), from the previous tick's stance
  if (t_rel_ >= 0.0 && t_after < 0.0) {
    for (int k = 0; k < 4; ++k) {
      if (sample_.contact[k] && !wbc_->stance()[k]) {
        w_search_.col(k) -= params_.touchdown_search_speed * dt * sample_.w_normal[k];
        const double len = w_search_.col(k).norm();
        if (len > params_.touchdown_search_max) w_search_.col(k) *= params_.touchdown_search_max / len;
      } else if (!sample_.contact[k]) {
        w_search_.col(k) *= 1.0 - dt / 0.2;
      }
    }
  }
  if (t_after >= 0.0 && !end_latched_) {
    w_search_end_ = w_search_;
    end_latched_ = true;
  }
  const Eigen::Matrix3d b_R_w = state.imu_quat.toRotationMatrix().transpose();
  if (params_.recover_time > 0.0 && t_after >= 0.0) {
    // recovery: quintic from the last pose back to the first one, even weight split
    const double s = std::min(1.0, t_after / params_.recover_time);
    const double h = s * s * s * (10.0 - 15.0 * s + 6.0 * s * s);
    const double dh = s < 1.0 ? 30.0 * s * s * (1.0 - s) * (1.0 - s) / params_.recover_time : 0.0;
    w_search_ = (1.0 - h) * w_search_end_;
    sample_.b_p_wheel = last_.b_p_wheel + h * (first_.b_p_wheel - last_.b_p_wheel) + b_R_w * w_search_;
    sample_.b_v_wheel = dh * (first_.b_p_wheel - last_.b_p_wheel);
    wbc_->setFootReferences(sample_.b_p_wheel, sample_.b_v_wheel);
    wbc_->setPlannedForces(sample_.w_F, true);
  } else {
    sample_.b_p_wheel += b_R_w * w_search_;
    wbc_->setFootReferences(sample_.b_p_wheel, sample_.b_v_wheel);
    wbc_->setPlannedForces(sample_.w_F);
  }
  if (params_.feedforward_acceleration) vdot_.head<6>() = sample_.vdot_base;
  wbc_->setBaseAcceleration(vdot_);
  wbc_->setContactNormals(sample_.w_normal);
  std::array<bool, 4> allowed = sample_.contact;
  for (int k = 0; k < 4; ++k) {
    if (allowed[k]) continue;
    for (double td : replay_.touchDowns(k)) {
      if (t_rel_ >= td - params_.early_touchdown && t_rel_ < td) allowed[k] = true;
    }
  }
  wbc_->setStanceMask(allowed);
  stabilizer_->update(state, dt, sample_.running, refs_);
  wbc_->setReferences(refs_);
  wbc_->tick(state, command);
}

}  // namespace centaur
