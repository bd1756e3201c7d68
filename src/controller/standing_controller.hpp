#pragma once
// Standing: hold the home posture with joint impedance plus a gravity-compensating torque feed-forward.
//
// Every tick (1 kHz):
//   1. base pose for the model: with use_base_estimator (default) the BaseEstimator's (IMU orientation,
//      position from leg kinematics with all four wheels in stance); otherwise orientation
//      w_R_base = w_R_imu * imu_R_base and position 0. Either way only the orientation matters here:
//      gravity and the base rows of the contact Jacobians depend on relative positions only.
//      Velocity zero (static balance).
//   2. g(q) from RobotModel; per-wheel contact point c_k = wheel centre - r e_z (W) and its Jacobian J_k.
//   3. static wheel forces F = [f_1..f_4] (12) balancing the 6 floating-base rows: J_b^T F = g_b, with
//      the weighted least-norm solution F = W^-1 A^T (A W^-1 A^T)^-1 g_b, A = J_b^T (6 x 12),
//      W = diag(w_t, w_t, 1) per wheel (tangential forces cost w_t times more than normal ones, so the
//      split uses the normal loads and moment arms, not friction); each f_k is then projected into its
//      friction cone (f_n >= 0, |f_t| <= mu f_n).
//   4. tau_ff = g_joints - sum_k J_k,joints^T f_k;  q_ref = home (wheels: the initial angle), qd_ref = 0,
//      kp/kd per joint group.
// tick() never allocates nor throws (all workspaces are sized in the constructor / start()).
#include <array>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "common/yaml_reader.hpp"
#include "controller/base_estimator.hpp"
#include "controller/robot_frames.hpp"
#include "controller/robot_interface.hpp"
#include "model/robot_model.hpp"

namespace centaur {

struct JointGains {
  double kp = 0.0;  ///< [Nm/rad]
  double kd = 0.0;  ///< [Nm s/rad]
};

struct StandingParams {
  // Per joint group (by joint name): leg = hip_yaw/hip_pitch/knee_pitch, arm = j_arm*_1..4,
  // wrist = j_arm*_5..7, other = any joint not matched.
  JointGains leg{1000.0, 10.0};
  JointGains ankle_pitch{500.0, 5.0};
  JointGains ankle_yaw{100.0, 1.0};
  JointGains wheel{100.0, 2.0};
  JointGains torso{500.0, 5.0};
  JointGains arm{300.0, 3.0};
  JointGains wrist{50.0, 0.5};
  JointGains other{100.0, 1.0};
  bool feedforward = true;           ///< gravity-compensating feed-forward on/off
  bool use_base_estimator = true;    ///< base pose from BaseEstimator (else IMU orientation, position 0)
  double tangential_weight = 100.0;  ///< [-] w_t, cost of tangential vs normal wheel forces
  double friction = 0.6;             ///< [-] mu assumed for the cone projection
  double wheel_radius = 0.078;       ///< [m]
  RobotFrames frames;                ///< the robot's names (not configuration keys: from its description)
  /// Per impedance group of frames.gain_patterns (key controller.gains.<group>), when there are patterns.
  std::map<std::string, JointGains> group_gains;

  /// Documented defaults of the `controller:` section (YAML with units and ranges).
  static const char* defaultsYaml();
  /// Read the section (strict: call finish() on the reader afterwards).
  void read(YamlReader& r);
};

/// The `gains:` lines of a `controller:` section (documented defaults, indented by two spaces).
const char* jointGainsDefaultsYaml();
/// Read a `gains:` section (strict) into the joint groups of p.
void readJointGains(YamlReader& gains, StandingParams& p);
/// The impedance gains of a joint, by its name (the groups above).
JointGains gainsFor(const std::string& joint_name, const StandingParams& p);

/// Safe mode (latched until resume()): entered on a non-finite measurement or on requestSafeMode(); the command
/// then holds the home posture with kd x safe_kd_scale (3) and the last good feed-forward.
class StandingController final : public SupervisedController {
 public:
  /// Loads the controller's own RobotModel from the MJCF (the model never reads the simulator's state).
  StandingController(const std::string& mjcf_path, const StandingParams& params);
  ~StandingController() override;

  void start(const RobotState& state, JointCommand& command) override;
  void tick(const RobotState& state, JointCommand& command) noexcept override;
  void requestSafeMode() noexcept override;
  void resume() noexcept override;
  ControllerReport report() const noexcept override;
  void triggerStart(double /*t*/) noexcept override {}  // no timeline: standing is the whole task
  const std::vector<std::string>& jointNames() const override { return model_->jointNames(); }

  const RobotModel& model() const { return *model_; }
  const StandingParams& params() const { return params_; }
  /// The base estimate used by the last tick (RobotModel's q layout, nq).
  const Eigen::VectorXd& baseConfiguration() const { return q_model_; }
  /// Wheel forces of the last tick (world frame, columns = wheels) [N].
  const Eigen::Matrix<double, 3, 4>& wheelForces() const { return forces_; }

 private:
  void computeFeedforward(const RobotState& state, JointCommand& command) noexcept;

  StandingParams params_;
  std::unique_ptr<RobotModel> model_;
  BaseEstimator estimator_;
  int n_ = 0;
  std::array<int, 4> wheel_ids_{};
  Eigen::Quaterniond imu_q_base_ = Eigen::Quaterniond::Identity();  // imu_R_base
  Eigen::VectorXd q_home_, kp_, kd_, kd_safe_, good_tau_ff_;
  bool safe_ = false, safe_requested_ = false, resume_pending_ = false;
  const char* safe_reason_ = "";
  // workspaces
  Eigen::VectorXd q_model_, v_model_, g_;
  std::array<RowMatrixXd, 4> J_;
  Eigen::Matrix<double, 6, 12> A_;
  Eigen::Matrix<double, 12, 1> w_inv_, F_;
  Eigen::Matrix<double, 6, 6> AWA_;
  Eigen::LDLT<Eigen::Matrix<double, 6, 6>> ldlt_;
  Eigen::Matrix<double, 3, 4> forces_ = Eigen::Matrix<double, 3, 4>::Zero();
};

}  // namespace centaur
