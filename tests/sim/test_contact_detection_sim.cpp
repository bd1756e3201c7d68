// ctest-labels: sim integration
// Wheel contact detection and force distribution in closed loop on CENTAURO in MuJoCo. The controller is
// built from the online components only (it never reads the simulator): BaseEstimator (stance flags = the
// detector's), RobotModel, ContactDetector on the measured joint torques, ForceDistribution over the
// DETECTED stance wheels for the torque feed-forward (vdot_d = 0, F_d = 0), joint impedance to home
// (StandingController's gains and references, its own feed-forward off). Wheel 3 (rear-left; the CoM
// stays inside the triangle of the other three) is lifted 6 cm by its leg and put down again.
// Checked against the simulator's ground-truth wheel forces: lift-off and touchdown are detected within
// 5 ms of the ground-truth normal force crossing the detector's thresholds, no other transition happens,
// and the estimated normal forces agree with the ground truth in steady stance. Second test: the robot
// dropped from 3 cm, every wheel's touchdown detected within 5 ms.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "controller/base_estimator.hpp"
#include "controller/contact_detector.hpp"
#include "controller/force_distribution.hpp"
#include "controller/standing_controller.hpp"
#include "sim/mujoco_robot.hpp"
#include "sim/sim_config.hpp"

using namespace centaur;
using namespace centaur::sim;
using Eigen::Vector3d;
using Eigen::VectorXd;

namespace {

constexpr int kLifted = 2;  // wheel_3
constexpr double kLiftStart = 0.3, kRamp = 0.15, kLowerStart = 0.8, kEnd = 1.3;

class LiftController final : public Controller {
 public:
  LiftController(const std::string& mjcf, bool lift) : standing_(mjcf, noFeedforward()), model_(mjcf), lift_(lift) {
    estimator_.init(mjcf);
    detector_.init(model_);
    distribution_.init(model_);
    // Joint offsets that raise wheel 3's centre by 6 cm at the home posture (a few Gauss-Newton steps on
    // the wheel-centre pose, leg joints hip_yaw .. ankle_yaw).
    const int n = model_.numJoints();
    for (const char* name : {"hip_yaw_3", "hip_pitch_3", "knee_pitch_3", "ankle_pitch_3", "ankle_yaw_3"}) {
      leg_.push_back(model_.jointIndex(name));
    }
    dq_lift_ = VectorXd::Zero(n);
    VectorXd q = VectorXd::Zero(model_.nq());
    q[3] = 1.0;
    q.tail(n) = model_.homeJoints();
    const int centre = model_.frameId("wheel_centre_3");
    model_.update(q, VectorXd::Zero(model_.nv()));
    const Eigen::Isometry3d target0 = model_.framePose(centre);
    const Vector3d target = target0.translation() + Vector3d(0, 0, 0.06);
    RowMatrixXd J(6, model_.nv());
    Eigen::MatrixXd Jl(6, static_cast<int>(leg_.size()));
    for (int it = 0; it < 5; ++it) {
      model_.update(q, VectorXd::Zero(model_.nv()));
      const Eigen::Isometry3d T = model_.framePose(centre);
      Eigen::Matrix<double, 6, 1> e;
      e.head<3>() = target - T.translation();
      const Eigen::AngleAxisd aa(target0.linear() * T.linear().transpose());
      e.tail<3>() = aa.angle() * aa.axis();
      model_.frameJacobian(centre, J);
      for (std::size_t j = 0; j < leg_.size(); ++j) Jl.col(static_cast<int>(j)) = J.col(6 + leg_[j]);
      const VectorXd dq = Jl.completeOrthogonalDecomposition().solve(e);
      for (std::size_t j = 0; j < leg_.size(); ++j) q[7 + leg_[j]] += dq[static_cast<int>(j)];
    }
    dq_lift_ = q.tail(n) - model_.homeJoints();
    vdot_ = VectorXd::Zero(model_.nv());
  }

  void start(const RobotState& state, JointCommand& command) override {
    standing_.start(state, command);
    tick(state, command);
  }

  void tick(const RobotState& state, JointCommand& command) noexcept override {
    standing_.tick(state, command);  // q_ref = home, gains; tau_ff = 0 (its feed-forward is off)
    bool stance[4];
    for (int k = 0; k < 4; ++k) stance[k] = detector_.inContact(k);
    estimator_.update(state, stance);
    model_.update(estimator_.q(), estimator_.v());
    if (first_ || state.t > t_prev_) {  // start() and the first period see the same t = 0 sample
      ok_ = detector_.update(model_, state.tau, first_ ? 0.0 : state.t - t_prev_) && ok_;
      first_ = false;
      t_prev_ = state.t;
    }
    for (int k = 0; k < 4; ++k) contacts_.stance[k] = detector_.inContact(k);
    status_ = distribution_.compute(model_, vdot_, ForceDistribution::Forces::Zero(), contacts_);
    if (status_ == ForceDistributionStatus::kOk) ++ok_count_;
    command.tau_ff = distribution_.tauFeedforward();
    const double t = state.t;
    double a = 0.0;  // lift fraction, smooth ramps
    if (t >= kLiftStart && t < kLowerStart) a = ramp((t - kLiftStart) / kRamp);
    if (t >= kLowerStart) a = 1.0 - ramp((t - kLowerStart) / kRamp);
    if (lift_) {
      for (int j : leg_) command.q_ref[j] += a * dq_lift_[j];
    }
  }

  /// Start in the air at a known base position: estimator from there, detector with no contact and r_0 = 0.
  void startInAir(const Vector3d& w_p_base) {
    estimator_.reset(w_p_base);
    detector_.reset({false, false, false, false}, false);
  }

  const ContactDetector& detector() const { return detector_; }
  const ForceDistribution& distribution() const { return distribution_; }
  bool ok() const { return ok_; }
  int okCount() const { return ok_count_; }

 private:
  static StandingParams noFeedforward() {
    StandingParams p;
    p.feedforward = false;
    return p;
  }
  static double ramp(double s) {
    s = std::min(1.0, std::max(0.0, s));
    return 0.5 - 0.5 * std::cos(M_PI * s);
  }

  StandingController standing_;
  RobotModel model_;
  BaseEstimator estimator_;
  ContactDetector detector_;
  ForceDistribution distribution_;
  WheelContacts contacts_;
  bool lift_ = true;
  std::vector<int> leg_;
  VectorXd dq_lift_, vdot_;
  bool first_ = true, ok_ = true;
  double t_prev_ = 0.0;
  int ok_count_ = 0;
  ForceDistributionStatus status_ = ForceDistributionStatus::kFailed;
};

TEST(ContactDetectionSim, LiftedAndRelandedWheelDetectedWithinFiveMilliseconds) {
  SimConfig cfg = loadSimConfig("", "", {});
  MujocoRobot robot(cfg.robot);
  LiftController ctrl(cfg.robot.model_path, true);
  const ContactDetectorParams& dp = ctrl.detector().params();
  RobotState state;
  state.resize(robot.numJoints());
  JointCommand command;
  robot.read(state);
  ctrl.start(state, command);

  Eigen::Matrix3Xd f_true(3, 4);
  const double dt = robot.controlPeriodSeconds();
  const int periods = static_cast<int>(std::lround(kEnd / dt));
  double t_gt_off = -1, t_gt_zero = -1, t_gt_on = -1, t_gt_touch = -1, t_det_off = -1, t_det_on = -1;
  int transitions[4] = {0, 0, 0, 0};
  bool prev[4] = {true, true, true, true};
  double max_hold_fz = 0.0;  // ground-truth force on the lifted wheel while it is held up
  double max_stance_err = 0.0, fz_at_det_off = -1, fz_at_det_on = -1;
  for (int i = 0; i < periods; ++i) {
    robot.controlPeriod(ctrl, state, command);
    // The measurement of this period was sampled at its start, state.t; the ground truth is from the last
    // physics step before that instant's successor, so compare at the same control-period index.
    robot.contactForces(f_true);
    const double t = state.t;
    const double fz = f_true(2, kLifted);
    if (t > kLiftStart && t < kLowerStart) {
      if (t_gt_off < 0 && fz < dp.off_threshold) t_gt_off = t;
      if (t_gt_zero < 0 && fz <= 0.0) t_gt_zero = t;
    }
    if (t > kLowerStart) {
      if (t_gt_touch < 0 && fz > 0.0) t_gt_touch = t;
      if (t_gt_on < 0 && fz > dp.on_threshold) t_gt_on = t;
    }
    if (t > kLiftStart + kRamp && t < kLowerStart) max_hold_fz = std::max(max_hold_fz, fz);
    for (int k = 0; k < 4; ++k) {
      const bool c = ctrl.detector().inContact(k);
      if (c != prev[k]) ++transitions[k];
      prev[k] = c;
    }
    const bool c3 = ctrl.detector().inContact(kLifted);
    if (t_det_off < 0 && !c3) {
      t_det_off = t;
      fz_at_det_off = fz;
    }
    if (t_det_off > 0 && t_det_on < 0 && c3) {
      t_det_on = t;
      fz_at_det_on = fz;
    }
    // Steady four-wheel stance before the lift and after the landing has settled.
    if ((t > 0.2 && t < kLiftStart) || t > kLowerStart + kRamp + 0.2) {
      for (int k = 0; k < 4; ++k) {
        max_stance_err = std::max(max_stance_err, std::abs(ctrl.detector().normalForce(k) - f_true(2, k)));
      }
    }
  }
  std::printf("ground truth: below %.0f N at %.4f s, zero at %.4f s; touch at %.4f s, above %.0f N at %.4f s\n",
              dp.off_threshold, t_gt_off, t_gt_zero, t_gt_touch, dp.on_threshold, t_gt_on);
  std::printf("detected: lift-off at %.4f s (true fz %.1f N), touchdown at %.4f s (true fz %.1f N)\n", t_det_off,
              fz_at_det_off, t_det_on, fz_at_det_on);
  std::printf("max |estimated - true| normal force in steady stance: %.2f N; distribution ok %d of %d\n",
              max_stance_err, ctrl.okCount(), periods + 1);

  EXPECT_TRUE(ctrl.ok());
  EXPECT_EQ(ctrl.okCount(), periods + 1) << "the distribution's floating-base rows held at every tick";
  ASSERT_GT(t_gt_zero, 0.0) << "the wheel never left the ground";
  EXPECT_EQ(max_hold_fz, 0.0) << "the wheel touched the ground while held up";
  ASSERT_GT(t_gt_on, 0.0) << "the wheel never landed";
  ASSERT_GT(t_det_off, 0.0);
  ASSERT_GT(t_det_on, 0.0);
  // Lift-off: not before the true force fell below off_threshold (minus one period of sampling offset),
  // at most 5 ms after.
  EXPECT_GE(t_det_off, t_gt_off - dt - 1e-9);
  EXPECT_LE(t_det_off, t_gt_off + 0.005 + 1e-9);
  EXPECT_LE(t_det_off, t_gt_zero + 0.005 + 1e-9);
  // Touchdown: after the wheel really touched, at most 5 ms after the true force exceeded on_threshold.
  EXPECT_GE(t_det_on, t_gt_touch - 1e-9);
  EXPECT_LE(t_det_on, t_gt_on + 0.005 + 1e-9);
  // Exactly one lift-off and one touchdown of wheel 3, nothing else.
  EXPECT_EQ(transitions[kLifted], 2);
  for (int k = 0; k < 4; ++k) {
    if (k != kLifted) {
      EXPECT_EQ(transitions[k], 0) << "wheel " << k + 1;
    }
  }
  EXPECT_LT(max_stance_err, 0.1 * ctrl.distribution().forces().row(2).sum() / 4);
  // The robot stayed up: pelvis height and attitude.
  EXPECT_GT(robot.basePosition().z(), 0.6);
  EXPECT_GT((robot.baseOrientation() * Vector3d::UnitZ()).z(), std::cos(3.0 * M_PI / 180.0));
}

TEST(ContactDetectionSim, DroppedRobotTouchdownOfEveryWheelDetectedWithinFiveMilliseconds) {
  // CENTAURO released 3 cm above the ground in its home posture; the controller knows the start pose and
  // that no wheel touches; the detector starts with r_0 = 0. Each wheel's first touchdown is detected
  // within 5 ms of the true normal force exceeding on_threshold (the impact is sharp: ~1 kN at once); the
  // robot bounces (ground truth through the same hysteresis shows it): no invented transition.
  SimConfig cfg = loadSimConfig("", "", {});
  MujocoRobot robot(cfg.robot);
  robot.data()->qpos[2] += 0.03;  // free joint first: qpos[0..2] = pelvis position
  mj_forward(robot.model(), robot.data());
  LiftController ctrl(cfg.robot.model_path, false);
  const double on = ctrl.detector().params().on_threshold;
  ctrl.startInAir(robot.basePosition());
  RobotState state;
  state.resize(robot.numJoints());
  JointCommand command;
  robot.read(state);
  ctrl.start(state, command);
  ASSERT_FALSE(ctrl.detector().inContact(0));

  Eigen::Matrix3Xd f_true(3, 4);
  const double dt = robot.controlPeriodSeconds();
  double t_touch[4] = {-1, -1, -1, -1}, t_on[4] = {-1, -1, -1, -1}, t_det[4] = {-1, -1, -1, -1};
  int transitions[4] = {0, 0, 0, 0}, gt_transitions[4] = {0, 0, 0, 0};
  bool prev[4] = {false, false, false, false}, gt[4] = {false, false, false, false};
  const double off = ctrl.detector().params().off_threshold;
  for (int i = 0; i < static_cast<int>(std::lround(0.4 / dt)); ++i) {
    robot.controlPeriod(ctrl, state, command);
    robot.contactForces(f_true);
    for (int k = 0; k < 4; ++k) {
      if (t_touch[k] < 0 && f_true(2, k) > 0.0) t_touch[k] = state.t;
      if (t_on[k] < 0 && f_true(2, k) > on) t_on[k] = state.t;
      // ground truth through the same hysteresis (no debounce): real bounces
      if (gt[k] ? f_true(2, k) < off : f_true(2, k) > on) {
        gt[k] = !gt[k];
        ++gt_transitions[k];
      }
      const bool c = ctrl.detector().inContact(k);
      if (t_det[k] < 0 && c) t_det[k] = state.t;
      if (c != prev[k]) ++transitions[k];
      prev[k] = c;
    }
  }
  EXPECT_TRUE(ctrl.ok());
  for (int k = 0; k < 4; ++k) {
    std::printf("wheel %d: true touch %.4f s, above %.0f N %.4f s; detected %.4f s; transitions %d (true %d)\n",
                k + 1, t_touch[k], on, t_on[k], t_det[k], transitions[k], gt_transitions[k]);
    ASSERT_GT(t_touch[k], 0.05) << "wheel " << k + 1 << " fell ~3 cm first";
    ASSERT_GT(t_det[k], 0.0) << "wheel " << k + 1;
    EXPECT_GE(t_det[k], t_touch[k] - 1e-9) << "wheel " << k + 1;
    EXPECT_LE(t_det[k], t_on[k] + 0.005 + 1e-9) << "wheel " << k + 1;
    EXPECT_TRUE(ctrl.detector().inContact(k)) << "wheel " << k + 1;
    // Bounces: the detector may miss a short one (low-pass + debounce) but never invents one.
    EXPECT_LE(transitions[k], gt_transitions[k]) << "wheel " << k + 1;
  }
  EXPECT_GT((robot.baseOrientation() * Vector3d::UnitZ()).z(), std::cos(3.0 * M_PI / 180.0));
}

}  // namespace
