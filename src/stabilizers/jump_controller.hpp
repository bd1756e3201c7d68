#pragma once
// The online stage of a jump (paper Sec. IV, Fig. 2): primitive replay + upper-body stabilizer + whole-body
// controller (HQP IK, contact detection, force distribution), behind the Controller interface at 1 kHz.
//
// Timeline (robot time t, t0 = time of start()):
//   [t0, t0 + settle_time)                 hold the primitive's first sample (the robot settles on its wheels;
//                                          the stabilizer may prepare, e.g. the OCP arm trajectory blends in)
//   [t0 + settle_time, + duration)         replay: every tick the sample at t - t0 - settle_time
//   [.., + recover_time)                   recovery (if recover_time > 0): r_C goes back from the last sample to
//                                          the first one along a quintic (zero velocity and acceleration at
//                                          both ends), forces = the even weight split; then hold the first
//                                          sample (the robot stands as it started). recover_time = 0: hold
//                                          the last sample (e.g. the half-squat jump stays on the wall).
// Per tick, before WholeBodyController::tick():
//   setFootReferences(r_C, r_C dot)   the planned pelvis -> wheel-centre positions (first stack level),
//   setPlannedForces(F_C)             the planned contact forces (force distribution),
//   setBaseAcceleration([a, alpha, 0])  the planned base acceleration (force distribution),
//   setContactNormals(n)              the planned surface of each wheel (ground +z, wall +x),
//   setStanceMask(allowed)            contact reconciliation: a wheel may be in stance if it is planned in
//                                     contact, or within `early_touchdown` seconds before its planned
//                                     touch-down (early touch-down); the detector decides within that set
//                                     (late touch-down: planned but not detected -> not in stance; late
//                                     lift-off: detected but planned in flight -> not in stance),
//   stabilizer->update(...)           posture / pelvis / momentum references.
// Late touch-down search: a wheel planned in contact but not detected in stance moves on along -n (its
// surface's normal) at touchdown_search_speed, up to touchdown_search_max, on top of the planned r_C; the offset
// is held while the wheel is in stance, decays (time constant 0.2 s) while it is planned in flight, and is
// blended out with the recovery. So a robot that flies higher or lands behind the plan still reaches the
// ground or the wall instead of waving its legs in the air.
// tick() never allocates and never throws.
#include <memory>
#include <string>

#include "controller/primitive_replay.hpp"
#include "controller/whole_body_controller.hpp"
#include "stabilizers/stabilizer.hpp"

namespace centaur {

class YamlReader;

struct JumpControllerParams {
  double settle_time = 0.5;       ///< [s] before the primitive starts, [0, 10]
  double early_touchdown = 0.08;  ///< [s] window before a planned touch-down in which contact is accepted, [0, 1]
  double touchdown_search_speed = 0.3;  ///< [m/s] late touch-down search speed (0: off), [0, 5]
  double touchdown_search_max = 0.15;   ///< [m] largest search offset, [0, 0.5]
  double recover_time = 0.0;      ///< [s] back to the first sample's r_C after the end (0: hold the last), [0, 10]
  /// When the primitive starts: "settle" = settle_time after start(); "trigger" = at triggerStart(t), but not
  /// before settle_time (until then the first sample is held).
  std::string start = "settle";
  bool feedforward_acceleration = true;  ///< pass the planned base acceleration to the force distribution
  WholeBodyParams wbc;            ///< stack_yaml is filled from the stabilizer
  /// The documented defaults of the scenario's `controller:` section (stabilizer sections included).
  static std::string defaultsYaml();
  /// Read everything except the stabilizer sections (strict: finish() afterwards, by the caller).
  void read(YamlReader& r);
};

class JumpController final : public SupervisedController {
 public:
  /// Builds the whole-body controller with the stabilizer's stack. Throws InputError (bad model, stack, primitive).
  JumpController(const std::string& mjcf_path, const data::Primitive& primitive,
                 std::unique_ptr<Stabilizer> stabilizer, const JumpControllerParams& params);

  void start(const RobotState& state, JointCommand& command) override;
  void tick(const RobotState& state, JointCommand& command) noexcept override;
  void requestSafeMode() noexcept override { wbc_->requestSafeMode(); }
  void resume() noexcept override { wbc_->resume(); }
  /// phase: "waiting" (for the trigger), "settle", "primitive", "recover" or "end".
  ControllerReport report() const noexcept override;
  void triggerStart(double t) noexcept override;
  const std::vector<std::string>& jointNames() const override { return wbc_->ikModel().jointNames(); }

  const WholeBodyController& wholeBody() const { return *wbc_; }
  const PrimitiveReplay& replay() const { return replay_; }
  const Stabilizer& stabilizer() const { return *stabilizer_; }
  const ReplaySample& lastSample() const { return sample_; }
  /// Late touch-down search offsets of the wheels (W) [m].
  const Eigen::Matrix<double, 3, 4>& searchOffsets() const { return w_search_; }
  /// Time since the primitive's start (negative while settling) [s].
  double primitiveTime() const { return t_rel_; }
  /// Primitive start time (robot time) [s]; +inf while waiting for the trigger.
  double primitiveStart() const;

 private:
  JumpControllerParams params_;
  PrimitiveReplay replay_;
  std::unique_ptr<Stabilizer> stabilizer_;
  std::unique_ptr<WholeBodyController> wbc_;
  WholeBodyReferences refs_;  // the stabilizer's references of the period (sized once)
  ReplaySample sample_, first_, last_;
  Eigen::VectorXd vdot_;
  Eigen::Matrix<double, 3, 4> w_search_ = Eigen::Matrix<double, 3, 4>::Zero(), w_search_end_ = w_search_;
  bool end_latched_ = false;
  bool use_trigger_ = false, triggered_ = false;
  double t0_ = 0.0, t_rel_ = 0.0, t_trigger_ = 0.0;
};

}  // namespace centaur
