#pragma once
// Wheel contact detection from measured joint torques.
//
// 1. Generalized-momentum observer (De Luca et al.): with p = M(q) v and M vdot + C v + g = S' tau + tau_ext,
//      pdot = S' tau + C' v - g + tau_ext      (since Mdot = C + C'),
//    the residual  r(t) = K ( p(t) - p(0) - int_0^t (S' tau + C' v - g + r) ds )  obeys  rdot = K (tau_ext - r):
//    a first-order low-pass (time constant 1/K) of the external generalized force, with no acceleration.
//    Discretely (period dt, the caller's): C' v - g = Mdot v - b with b = C v + g from RobotModel and
//    Mdot v dt ~ (M_k - M_{k-1}) v_k, so
//      I_k = I_{k-1} + dt (S' tau_k - b_k + r_{k-1}) + (M_k - M_{k-1}) v_k,    r_k = K (M_k v_k - p_0 - I_k).
//    Start: by default the first update() assumes a quasi-static robot and sets r_0 = b_0 - S' tau_0 (torque
//    residual with zero acceleration), so a robot that starts standing is detected in stance from the first
//    tick; reset(..., false) starts at r_0 = 0 instead (e.g. a robot that starts in the air).
// 2. Per wheel k: the rows of r of its leg's joints (hip_yaw_k .. j_wheel_k) are J_k,leg' F_k (legs are
//    separate chains), so F_k = pinv(J_k,leg') r_leg = (J_k,leg J_k,leg')^-1 J_k,leg r_leg (W, the force of
//    the ground ON the wheel), J_k the Jacobian of the wheel's material point at its contact point
//    (wheel centre - radius along the surface normal, as in ForceDistribution).
// 3. Normal force f_n = n_k' F_k with hysteresis: off -> on when f_n > on_threshold for on_debounce
//    consecutive updates, on -> off when f_n < off_threshold for off_debounce consecutive updates.
//
// Inputs: the caller's RobotModel update()d with the current (estimated) q, v (e.g. from BaseEstimator;
// the base velocity enters p) and the measured joint torques (RobotState::tau). No simulator access.
// Model/Data split: init() allocates; update() never allocates nor throws (a non-finite input or a step
// before init() is ignored and reported by returning false).
#include <array>
#include <string>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "model/robot_model.hpp"

namespace centaur {

class YamlReader;

struct ContactDetectorParams {
  double observer_gain = 500.0;  ///< [1/s] K (time constant 1/K); K dt must stay below 1, [1, 1e4]
  double on_threshold = 60.0;    ///< [N] normal force above which a wheel touches down, (off, 1e4]
  double off_threshold = 30.0;   ///< [N] normal force below which a wheel lifts off, [0, on)
  int on_debounce = 2;           ///< [updates] consecutive samples above on_threshold, [1, 100]
  int off_debounce = 2;          ///< [updates] consecutive samples below off_threshold, [1, 100]
  double wheel_radius = 0.078;   ///< [m] (0.01, 0.5]
  std::array<std::string, 4> wheel_bodies = {"wheel_1", "wheel_2", "wheel_3", "wheel_4"};
  std::array<std::string, 4> wheel_centres = {"wheel_centre_1", "wheel_centre_2", "wheel_centre_3",
                                              "wheel_centre_4"};
  /// Joints of wheel k's leg (their rows of the residual carry only that wheel's force).
  std::array<std::vector<std::string>, 4> leg_joints = {
      std::vector<std::string>{"hip_yaw_1", "hip_pitch_1", "knee_pitch_1", "ankle_pitch_1", "ankle_yaw_1",
                               "j_wheel_1"},
      std::vector<std::string>{"hip_yaw_2", "hip_pitch_2", "knee_pitch_2", "ankle_pitch_2", "ankle_yaw_2",
                               "j_wheel_2"},
      std::vector<std::string>{"hip_yaw_3", "hip_pitch_3", "knee_pitch_3", "ankle_pitch_3", "ankle_yaw_3",
                               "j_wheel_3"},
      std::vector<std::string>{"hip_yaw_4", "hip_pitch_4", "knee_pitch_4", "ankle_pitch_4", "ankle_yaw_4",
                               "j_wheel_4"}};

  /// Documented defaults of a `contact_detector:` section (YAML, units and ranges).
  static const char* defaultsYaml();
  /// Read the section's scalar keys (strict: call finish() on the reader afterwards). Throws InputError.
  void read(YamlReader& r);
};

class ContactDetector {
 public:
  static constexpr int kWheels = 4;
  using Forces = Eigen::Matrix<double, 3, kWheels>;

  /// Resolves frames and joints in the model and sizes every workspace (allocates). Throws InputError.
  void init(const RobotModel& model, const ContactDetectorParams& params = ContactDetectorParams());
  /// Restart the observer at the next update() with the given contact states; quasi_static_start: r_0 =
  /// b_0 - S' tau_0 (robot at rest), else r_0 = 0 (no external force, e.g. in the air).
  void reset(const std::array<bool, kWheels>& in_contact = {true, true, true, true},
             bool quasi_static_start = true);
  /// Surface normal of wheel k (W, unit; default e_z), used for the contact point and f_n.
  void setNormal(int k, const Eigen::Vector3d& n);

  /// One observer step: model update()d with the current q, v; tau (n) the measured joint torques;
  /// dt [s] the time since the previous update (ignored on the first). Returns false (and changes
  /// nothing) on invalid input. Never allocates, never throws.
  bool update(const RobotModel& model, const Eigen::Ref<const Eigen::VectorXd>& tau, double dt) noexcept;

  // ---- results of the last update() ----
  const std::array<bool, kWheels>& inContact() const { return contact_; }
  bool inContact(int k) const { return contact_[k]; }
  const Forces& forces() const { return F_; }     ///< [N] estimated wheel forces (W), on the wheel
  double normalForce(int k) const { return fn_[k]; }  ///< [N] n_k' F_k
  const Eigen::VectorXd& residual() const { return r_; }  ///< [N, Nm] r (nv), ~ external generalized force
  const ContactDetectorParams& params() const { return params_; }

 private:
  ContactDetectorParams params_;
  bool initialized_ = false, started_ = false, quasi_static_start_ = true;
  int nv_ = 0, n_ = 0;
  std::array<int, kWheels> body_{}, centre_{};
  std::array<std::vector<int>, kWheels> dofs_;  // velocity indices (6 + joint) of each leg's joints
  std::array<Eigen::Vector3d, kWheels> normal_;
  RowMatrixXd M_, M_prev_, J_;
  Eigen::VectorXd b_, p0_, I_, r_, tmp_;
  Eigen::MatrixXd Jleg_;   // 3 x leg size (max), workspace
  Eigen::VectorXd rleg_;
  Eigen::LDLT<Eigen::Matrix3d> ldlt_;
  Forces F_ = Forces::Zero();
  std::array<double, kWheels> fn_{};
  std::array<bool, kWheels> contact_{};
  std::array<int, kWheels> count_{};
};

}  // namespace centaur
