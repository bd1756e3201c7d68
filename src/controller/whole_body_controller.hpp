#pragma once
// The 1 kHz whole-body tick: velocity-level hierarchical IK + contact force distribution.
//
// Every tick (period dt):
//   1. input check: any NaN/Inf in the RobotState -> safe mode (below);
//   2. BaseEstimator::update(state, stance of the previous tick's contact detector) -> q, v (RobotModel layout),
//      on the "measured" RobotModel, which it leaves at (q, v) (one model update, shifted to the estimate);
//   3. ContactDetector::update on the measured model (momentum observer) -> stance set;
//   4. the "IK" RobotModel at [estimated base pose, q_ref joints], [estimated base twist, qd_ref]: the IK runs
//      on its own integrated joint reference (open-loop IK, it never fights the impedance tracking error);
//   5. HQP (the YAML stack, decision variable x = v: nv = 6 + n) update() + solve(x);
//   6. qd_ref = x.tail(n), q_ref += qd_ref dt (the base twist part of x is not integrated: the base moves as the
//      contacts let it);
//   7. ForceDistribution on the measured model: vdot_d (default 0), planned forces F_d (default: the weight
//      split evenly on the stance wheels), stance from the detector -> tau_ff, clamped to the effort limits;
//   8. JointCommand: q_ref, qd_ref, tau_ff, kp, kd.
// References (hooks for the replay / stabilizers): setFootReferences (pelvis -> wheel centre, base frame),
// setPlannedForces, setBaseAcceleration, setPostureReference, setPelvisAngularVelocity, setAngularMomentum.
// Defaults after start() (and resume()): every Cartesian task (feet) and Com task held where it is, posture = home
// (wheels: their initial angle), zero angular velocity and momentum.
//
// Safe mode (latched until resume()): entered on a non-finite input (kSafeInvalidInput), a failed or non-finite
// HQP solution (kSafeQpFailed) or a non-finite estimate (kSafeInvalidInput). While in it the command is
//   q_ref = last good q_ref, qd_ref = 0, tau_ff = last good tau_ff (gravity compensation of the last good tick),
//   kp = nominal, kd = safe_kd_scale * nominal;
// it never contains NaN. A failed force distribution alone is not a safe-mode cause: tau_ff keeps its last good
// value and counters().force_failures counts it.
// start() allocates everything (and may throw InputError); tick() never allocates and never throws.
#include <array>
#include <memory>
#include <string>

#include <Eigen/Core>

#include "controller/base_estimator.hpp"
#include "controller/contact_detector.hpp"
#include "controller/force_distribution.hpp"
#include "controller/robot_frames.hpp"
#include "controller/robot_interface.hpp"
#include "controller/standing_controller.hpp"
#include "model/robot_model.hpp"
#include "qp/hqp_solver.hpp"
#include "qp/stack_yaml.hpp"

namespace centaur {

class CartesianTask;
class PosturalTask;
class PelvisAngularVelocityTask;
class AngularMomentumTask;

struct WholeBodyParams {
  std::string stack_file;            ///< YAML stack file (e.g. config/stack_stand.yaml), or
  std::string stack_yaml;            ///< the stack as YAML text (used when stack_file is empty)
  double dt = 0.001;                 ///< [s] control period (IK integration, observer step)
  StandingParams impedance;          ///< joint gains per group (and wheel_radius / friction are NOT used here)
  double safe_kd_scale = 3.0;        ///< [-] kd multiplier in safe mode, [1, 100]
  bool use_contact_detector = true;  ///< stance from the detector (false: all four wheels always in stance)
  ForceDistributionParams force;
  ContactDetectorParams detector;
  BaseEstimatorParams estimator;
  /// The robot's names and foot radii: the constructor gives them to the estimator, the contact detector and the
  /// force distribution (their own name and radius fields are overwritten). Set impedance.frames alike before
  /// reading the gains.
  RobotFrames frames;
  /// Names of the stack's tasks the reference hooks address (a missing name makes that hook a no-op).
  std::array<std::string, 4> foot_tasks = {"wheel_1", "wheel_2", "wheel_3", "wheel_4"};
  std::string pelvis_task = "pelvis", momentum_task = "ang_mom", posture_task = "posture";
};

enum class WholeBodyStatus {
  kNotStarted = 0,
  kOk,                ///< nominal tick
  kSafeInvalidInput,  ///< safe mode: NaN/Inf in the state or the estimate
  kSafeQpFailed,      ///< safe mode: the HQP failed (or returned a non-finite solution)
  kSafeRequested,     ///< safe mode: asked for from outside (requestSafeMode(), e.g. the robot's state went stale)
};
const char* toString(WholeBodyStatus status);

struct WholeBodyCounters {
  long ticks = 0;           ///< tick() calls
  long safe_ticks = 0;      ///< ticks spent in safe mode
  long invalid_inputs = 0;  ///< ticks with a non-finite input or estimate
  long qp_failures = 0;     ///< failed HQP solves
  long force_failures = 0;  ///< failed force distributions (tau_ff kept)
  long force_relaxed = 0;   ///< relaxed force distributions
};

/// The references an upper-body stabilizer hands the whole-body controller each period; setReferences() applies
/// those whose bit is set. The vectors are sized once (n joints) by whoever owns the struct.
struct WholeBodyReferences {
  enum : unsigned { kPosture = 1u, kPostureVelocity = 2u, kPelvisAngularVelocity = 4u, kAngularMomentum = 8u };
  unsigned set = 0;                                          ///< which references this period carries
  Eigen::VectorXd q_posture;                                 ///< [rad] posture reference of all n joints
  Eigen::VectorXd qd_posture;                                ///< [rad/s] its velocity feed-forward
  Eigen::Vector3d w_omega_pelvis = Eigen::Vector3d::Zero();  ///< [rad/s] pelvis angular velocity, W
  Eigen::Vector3d h_angular = Eigen::Vector3d::Zero();       ///< [kg m^2/s] centroidal angular momentum, W
  void resize(int n) {
    q_posture.setZero(n);
    qd_posture.setZero(n);
  }
};

class WholeBodyController final : public Controller {
 public:
  using Forces = Eigen::Matrix<double, 3, 4>;

  /// Loads two RobotModels from the MJCF, the stack (registerRobotTasks types) and sizes every workspace.
  /// Throws InputError naming the file for a bad model or stack.
  WholeBodyController(const std::string& mjcf_path, const WholeBodyParams& params);
  ~WholeBodyController() override;

  void start(const RobotState& state, JointCommand& command) override;
  void tick(const RobotState& state, JointCommand& command) noexcept override;

  // ---- reference hooks (no allocation; take effect at the next tick) ----
  /// Wheel-centre positions relative to the pelvis (base frame, columns = wheels) and their velocities.
  void setFootReferences(const Eigen::Matrix<double, 3, 4>& b_p_wheel,
                         const Eigen::Matrix<double, 3, 4>& b_v_wheel = Eigen::Matrix<double, 3, 4>::Zero());
  /// Planned wheel forces (W, on the wheel); use_default = true goes back to the even weight split.
  void setPlannedForces(const Forces& F_d, bool use_default = false);
  /// Desired generalized acceleration for the force distribution (nv, default 0).
  void setBaseAcceleration(const Eigen::Ref<const Eigen::VectorXd>& vdot_d) { vdot_d_ = vdot_d; }
  /// Posture reference of all n joints [rad] (e.g. a stabilizer's upper-body targets).
  void setPostureReference(const Eigen::Ref<const Eigen::VectorXd>& q_d);
  /// Velocity feed-forward of the posture reference, all n joints [rad/s] (default 0).
  void setPostureVelocity(const Eigen::Ref<const Eigen::VectorXd>& qd_d);
  void setPelvisAngularVelocity(const Eigen::Vector3d& w_omega_d);
  void setAngularMomentum(const Eigen::Vector3d& h_ang_d);
  /// The references whose bit is set in r.set (sizes as the model's). No allocation.
  void setReferences(const WholeBodyReferences& r) noexcept;
  /// InputError naming `who` and the task unless the stack has the task that takes each reference of `mask`
  /// (WholeBodyReferences bits): a reference without its task would be dropped silently.
  void requireTasks(unsigned mask, const std::string& who) const;
  /// Unit surface normal (W) of each wheel's (current or next) contact: used by the contact detector and the
  /// force distribution (default +z, flat ground).
  void setContactNormals(const std::array<Eigen::Vector3d, 4>& w_normal) noexcept;
  /// Which wheels MAY be in stance (default all): the stance set used by the estimator and the force
  /// distribution is (detected contact AND allowed). The replay uses it to reconcile the plan with the
  /// detector (a wheel planned in flight is not pushed on even if the detector still sees it in contact).
  void setStanceMask(const std::array<bool, 4>& allowed) noexcept { stance_mask_ = allowed; }
  /// Leave safe mode at the next tick with a valid input: q_ref := measured q, feet held where they are.
  void resume() noexcept {
    resume_pending_ = true;
    safe_requested_ = false;
  }
  /// Enter safe mode at the next tick (kSafeRequested), latched until resume().
  void requestSafeMode() noexcept {
    safe_requested_ = true;
    resume_pending_ = false;
  }

  // ---- results ----
  WholeBodyStatus status() const { return status_; }
  bool inSafeMode() const {
    return status_ == WholeBodyStatus::kSafeInvalidInput || status_ == WholeBodyStatus::kSafeQpFailed ||
           status_ == WholeBodyStatus::kSafeRequested;
  }
  const WholeBodyCounters& counters() const { return counters_; }
  QpStatus lastQpStatus() const { return qp_status_; }
  /// Wall time of the last tick's HQP update+solve [s] (steady clock), for benchmarks.
  double lastQpSeconds() const { return qp_seconds_; }
  const Eigen::VectorXd& solution() const { return x_; }  ///< x = v of the last solve (nv)
  /// The default posture reference since start(): the home keyframe, wheels at their initial angle [rad] (n).
  const Eigen::VectorXd& homePosture() const { return q_home_; }
  const RobotModel& ikModel() const { return *model_ik_; }
  const RobotModel& measuredModel() const { return *model_meas_; }
  HqpSolver& hqp() { return hqp_; }
  const LoadedStack& stack() const { return stack_; }
  const std::array<bool, 4>& stance() const { return contacts_.stance; }
  const ForceDistribution& forceDistribution() const { return force_; }
  const BaseEstimator& estimator() const { return estimator_; }
  const WholeBodyParams& params() const { return params_; }

 private:
  bool finiteInput(const RobotState& s) const noexcept;
  void holdCurrentReferences() noexcept;
  bool estimate(const RobotState& state) noexcept;
  void distributeForces() noexcept;
  void enterSafe(WholeBodyStatus why, JointCommand& command) noexcept;
  void writeSafe(JointCommand& command) noexcept;

  WholeBodyParams params_;
  std::unique_ptr<RobotModel> model_meas_, model_ik_;
  RobotModel::Detail ik_detail_ = RobotModel::Detail::kMomentum;  // kJacobians if no CoM/momentum task
  BaseEstimator estimator_;
  ContactDetector detector_;
  ForceDistribution force_;
  TaskRegistry registry_;
  LoadedStack stack_;
  HqpSolver hqp_;
  std::array<std::shared_ptr<CartesianTask>, 4> feet_;
  std::shared_ptr<PosturalTask> posture_;
  std::shared_ptr<PelvisAngularVelocityTask> pelvis_;
  std::shared_ptr<AngularMomentumTask> momentum_;
  int n_ = 0, nq_ = 0, nv_ = 0;
  Eigen::VectorXd kp_, kd_, kd_safe_, q_home_, tau_max_;
  Eigen::VectorXd q_ref_, qd_ref_, x_, q_ik_, v_ik_, vdot_d_;
  Eigen::VectorXd good_q_ref_, good_tau_ff_;
  WheelContacts contacts_;
  std::array<bool, 4> stance_mask_ = {true, true, true, true};
  Forces F_d_ = Forces::Zero();
  bool default_forces_ = true;
  bool resume_pending_ = false;
  bool safe_requested_ = false;
  WholeBodyStatus status_ = WholeBodyStatus::kNotStarted;
  WholeBodyCounters counters_;
  QpStatus qp_status_ = QpStatus::kOptimal;
  double qp_seconds_ = 0.0;
};

}  // namespace centaur
