#pragma once
// Floating-base state for the controller, from what the robot interface gives (RobotState) and the
// controller's knowledge of which wheels are in stance. Never reads a simulator.
//
// Estimator (documented in docs/model.md, "Base estimator"):
//   orientation  w_R_base = imu_quat (the IMU frame is rotated like the pelvis, imu_link is fixed to it
//                with zero rpy);
//   angular vel. b_omega_base = imu_omega (IMU frame = base frame);
//   joints       q, qd as measured;
//   position, in stance (at least one stance wheel): every stance wheel k keeps an anchor, the world
//                position of its wheel centre, stored at touchdown (= current base estimate + the
//                kinematic pelvis-to-wheel vector) and advanced while in stance by the pure-rolling
//                velocity of the wheel centre, omega_wheel x (centre - contact point) (zero when the wheel
//                does not spin, so a static stance never drifts). Then
//                  w_p_base = mean over stance wheels of (anchor_k - (w_p_wheel_k - w_p_base)_kinematics);
//   linear vel., in stance: the wheel's contact point (lowest point of the wheel rim) does not move
//                (rolling without slipping): w_v_base = mean over stance wheels of the base velocity that
//                makes that point's velocity zero, given the IMU angular velocity and the joint velocities;
//   in flight (no stance wheel): the CoM is ballistic from the take-off estimate,
//                p_com(t) = p_com0 + v_com0 tau + g tau^2 / 2, v_com = v_com0 + g tau, and the base
//                position/velocity follow from the kinematic base-to-CoM offset and relative CoM velocity.
//   initial position: reset(...) gives it; without reset(), the first update() puts x = y = 0 and z such
//                that the stance wheels' contact points are on average at z = 0 (flat ground).
// Conventions: RobotModel's (q = [w_p_base, w_quat_base (w, x, y, z), joints], v = [w_v_base, b_omega_base,
// qd]). Wheel order: wheel_1 front-left, wheel_2 front-right, wheel_3 rear-left, wheel_4 rear-right.
// Model/Data split: init() allocates (a private RobotModel workspace, on the caller's description or the MJCF); update() never
// allocates nor throws.
#include <Eigen/Core>
#include <Eigen/Geometry>

#include <memory>
#include <string>

#include "controller/robot_interface.hpp"
#include "controller/robot_frames.hpp"
#include "model/robot_model.hpp"

namespace centaur {

struct BaseEstimatorParams {
  double wheel_radius = 0.078;  ///< [m] rolling radius of the wheels, in (0, 0.5]
  /// Per foot (FL, FR, RL, RR): the body that rolls or rests on the ground and the site at its centre.
  std::array<std::string, 4> wheel_bodies = RobotFrames().contact_bodies;
  std::array<std::string, 4> wheel_centres = RobotFrames().foot_centres;
};

class BaseEstimator {
 public:
  static constexpr int kWheels = 4;

  /// Builds the private kinematic model from the MJCF (needs the bodies and sites of params.wheel_bodies and
  /// params.wheel_centres); throws InputError naming the file. Allocates.
  void init(const std::string& mjcf_path, const BaseEstimatorParams& params = BaseEstimatorParams());
  /// The same on a model description the caller shares (no parse).
  void init(std::shared_ptr<const RobotModelDescription> model, const BaseEstimatorParams& params = BaseEstimatorParams());
  /// Sets the base position and linear velocity (W) at the next update() (e.g. the known start pose).
  void reset(const Eigen::Vector3d& w_p_base, const Eigen::Vector3d& w_v_base = Eigen::Vector3d::Zero());
  /// One estimation step with the measurement and the stance flags (wheel k-1 in stance). No allocation.
  void update(const RobotState& state, const bool stance[kWheels]) noexcept;
  /// The same estimate on the caller's model (same MJCF) instead of the private one, leaving that model
  /// update()d at the estimate q(), v() with at least `detail` (plus the momentum data in flight): the model is
  /// updated once, at the prediction (previous position and linear velocity, measured orientation and joints),
  /// and shifted to the estimate (RobotModel::shiftBase), which saves the caller a second update. No allocation.
  void update(const RobotState& state, const bool stance[kWheels], RobotModel& model,
              RobotModel::Detail detail) noexcept;

  /// Ground-contact point of a wheel on flat horizontal ground: the lowest point of the rim, given the
  /// non-spinning wheel-centre frame (site wheel_centre_k, z = wheel axis) and the radius. (W)
  static Eigen::Vector3d contactPoint(const Eigen::Isometry3d& w_T_centre, double radius) {
    const Eigen::Vector3d a = w_T_centre.linear().col(2);
    Eigen::Vector3d down = a.z() * a - Eigen::Vector3d::UnitZ();
    const double len = down.norm();
    down = len > 1e-6 ? Eigen::Vector3d(down / len) : Eigen::Vector3d(-Eigen::Vector3d::UnitZ());
    return w_T_centre.translation() + radius * down;
  }

  const Eigen::VectorXd& q() const { return q_; }  ///< nq, RobotModel conventions
  const Eigen::VectorXd& v() const { return v_; }  ///< nv, RobotModel conventions
  /// The anchor (world wheel-centre position) of wheel k while it is in stance.
  const Eigen::Vector3d& anchor(int k) const { return anchor_[k]; }
  bool initialized() const { return initialized_; }

 private:
  void estimate(const RobotState& state, const bool stance[kWheels], RobotModel& model,
                RobotModel::Detail stance_detail, RobotModel::Detail flight_detail) noexcept;

  std::unique_ptr<RobotModel> model_;
  BaseEstimatorParams params_;
  int f_wheel_[kWheels] = {-1, -1, -1, -1};
  int f_centre_[kWheels] = {-1, -1, -1, -1};
  Eigen::VectorXd q_, v_, q_tmp_, v_tmp_;
  RowMatrixXd Jc_;
  Eigen::Vector3d anchor_[kWheels];
  bool prev_stance_[kWheels] = {false, false, false, false};
  bool initialized_ = false;
  bool reset_pending_ = false;
  bool in_flight_ = false;
  Eigen::Vector3d reset_p_ = Eigen::Vector3d::Zero(), reset_v_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d com0_ = Eigen::Vector3d::Zero(), vcom0_ = Eigen::Vector3d::Zero();
  double t_prev_ = 0.0, t_takeoff_ = 0.0;
};

}  // namespace centaur
