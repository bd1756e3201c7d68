#pragma once
// Contact force distribution for the four wheels, a small QP on our dense QP solver.
//
// Given the robot's current state (a RobotModel the caller has update()d with q, v), desired generalized
// accelerations vdot_d (nv) and desired wheel forces F_d (3 x 4, world frame, force exerted BY the ground
// ON the wheel), find the wheel forces F (only the stance wheels' are variables; the others are exactly 0):
//
//   minimise    1/2 sum_i w_track ||F_i - F_d,i||^2 + 1/2 eps ||F||^2
//   subject to  M_u vdot_d + b_u = sum_i J_i,u^T F_i                (the 6 floating-base rows, HARD)
//               f_min <= n_i' F_i <= f_max                           (unilateral, per stance wheel)
//               |t_1,i' F_i| <= mu n_i' F_i,  |t_2,i' F_i| <= mu n_i' F_i   (linearized friction pyramid)
//
// and return the joint torque feed-forward of the actuated rows
//   tau_ff = M_a vdot_d + b_a - sum_i J_i,a^T F_i.
// M, b = C v + g and J_i (the Jacobian of the wheel's MATERIAL point at the contact point) come from RobotModel.
// Contact point: wheel centre (site wheel_centre_k) minus radius along the part of the surface normal n_i
// that is perpendicular to the wheel axis (for a wheel upright on flat ground: centre - r e_z; against a wall
// with normal +x: centre - r e_x). Tangents: t_1 = normalised e_x (or e_y if n ~ e_x) projected on the
// surface, t_2 = n x t_1 (ground: e_x, e_y). The pyramid's half-width is mu (an outer approximation of the
// cone; use friction = mu / sqrt(2) for an inner one).
//
// Choice: the floating-base rows are HARD equalities (the returned forces realise the desired base motion
// exactly whenever that is possible). When they are infeasible under the friction/unilateral limits (e.g. a
// desired acceleration the stance wheels cannot produce), a hard equality would leave no answer at all;
// then a second QP with the rows as a heavily weighted least-squares term,
//   + 1/2 w_dyn ||sum_i J_i,u^T F_i - (M_u vdot_d + b_u)||^2,
// is solved and the status says kRelaxed: the forces still respect friction and unilaterality and come as
// close as possible (in the weighted sense) to the needed base wrench. So the answer degrades gracefully
// and the caller knows. residual() is ||M_u vdot_d + b_u - sum J_u^T F|| in both cases.
//
// Model/Data split: init() allocates everything (the QPs are sized once for 4 wheels); compute() never
// allocates, never throws, and returns a status the caller must check. On kFailed the outputs keep the values
// of the last successful compute() (zero before the first one).
#include <array>
#include <limits>
#include <string>

#include <Eigen/Core>

#include "model/robot_model.hpp"
#include "qp/qp_solver.hpp"

namespace centaur {

class YamlReader;

/// Contact point of a wheel of radius r whose (non-spinning) centre frame is w_T_centre (z = wheel axis)
/// on a surface with unit normal n (W): centre - r * (n projected perpendicular to the axis, normalised);
/// centre - r n if n is (nearly) along the axis.
Eigen::Vector3d wheelContactPoint(const Eigen::Isometry3d& w_T_centre, double radius, const Eigen::Vector3d& n);

struct ForceDistributionParams {
  double friction = 0.6;         ///< [-] mu, half-width of the friction pyramid, [0.01, 5]
  double wheel_radius = 0.078;   ///< [m] (0.01, 0.5]
  double min_normal_force = 0.0; ///< [N] f_min of every stance wheel, [0, 1e4]
  double max_normal_force = 1e4; ///< [N] f_max, [f_min, 1e5]
  double tracking_weight = 1.0;  ///< [1/N^2] w_track, [0, 1e6]
  double regularization = 1e-8;  ///< [1/N^2] eps (keeps the Hessian positive definite), [1e-12, 1], see conditioned()
  double dynamics_weight = 1e4;  ///< [1/N^2] w_dyn of the relaxed problem, [1, 1e9]
  /// Wheel k (0..3): spinning body (material point) and non-spinning centre site (z = axis).
  std::array<std::string, 4> wheel_bodies = {"wheel_1", "wheel_2", "wheel_3", "wheel_4"};
  std::array<std::string, 4> wheel_centres = {"wheel_centre_1", "wheel_centre_2", "wheel_centre_3",
                                              "wheel_centre_4"};

  /// Documented defaults of a `force_distribution:` section (YAML, units and ranges).
  static const char* defaultsYaml();
  /// Read the section's keys (strict: call finish() on the reader afterwards). Throws InputError.
  void read(YamlReader& r);
  /// tracking_weight + regularization >= kMinRegularisationRatio * dynamics_weight: the relaxed QP's Hessian
  /// (tracking_weight + regularization) I + dynamics_weight J_u J_u' stays in the QP solver's accurate range.
  bool conditioned() const;
  std::string conditioningRule() const;  ///< the rule, for error messages
};

/// Which wheels touch what: stance flag and unit surface normal (W) per wheel (default: all on flat ground).
struct WheelContacts {
  std::array<bool, 4> stance = {true, true, true, true};
  std::array<Eigen::Vector3d, 4> normal = {Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitZ(),
                                           Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitZ()};
};

enum class ForceDistributionStatus {
  kOk = 0,   ///< the floating-base rows hold (hard equality), friction and unilateral limits respected
  kRelaxed,  ///< they could not hold under the limits: weighted least-squares compromise (see residual())
  kFailed,   ///< invalid input (NaN, bad normal, not initialised) or QP failure; outputs = last good ones
};
const char* toString(ForceDistributionStatus status);

class ForceDistribution {
 public:
  static constexpr int kWheels = 4;
  using Forces = Eigen::Matrix<double, 3, kWheels>;

  /// Resolves the wheel frames in the model and sizes every workspace (allocates). Throws InputError for an
  /// unknown frame or a parameter out of range.
  void init(const RobotModel& model, const ForceDistributionParams& params = ForceDistributionParams());

  /// One distribution on the model's last update() (q, v). vdot_d: nv; F_d: desired forces (W), columns =
  /// wheels (ignored for wheels not in stance). Never allocates, never throws.
  [[nodiscard]] ForceDistributionStatus compute(const RobotModel& model,
                                                const Eigen::Ref<const Eigen::VectorXd>& vdot_d,
                                                const Forces& F_d, const WheelContacts& contacts) noexcept;

  // ---- results of the last compute() ----
  const Forces& forces() const { return F_; }               ///< [N] (W), zero columns for swing wheels
  const Eigen::VectorXd& tauFeedforward() const { return tau_ff_; }  ///< [Nm] n joints (RobotModel order)
  double residual() const { return residual_; }  ///< [N, Nm] ||M_u vdot_d + b_u - sum J_u^T F||
  ForceDistributionStatus status() const { return status_; }
  /// Contact point of wheel k used by the last compute() (W).
  const Eigen::Vector3d& contactPoint(int k) const { return w_contact_[k]; }
  /// 3 x nv Jacobian of wheel k's contact point of the last compute().
  const RowMatrixXd& contactJacobian(int k) const { return J_[k]; }
  const ForceDistributionParams& params() const { return params_; }
  bool initialized() const { return initialized_; }
  /// QP active-set iterations of the last compute() (hard + relaxed).
  int iterations() const { return iterations_; }

 private:
  ForceDistributionParams params_;
  bool initialized_ = false;
  int nv_ = 0, n_ = 0;
  std::array<int, kWheels> body_{}, centre_{};
  std::array<RowMatrixXd, kWheels> J_;
  std::array<Eigen::Vector3d, kWheels> w_contact_;
  RowMatrixXd M_;
  Eigen::VectorXd b_, Mvb_;  // b, M vdot_d + b
  // QP data (sized for 12 variables, 6 equalities, 20 inequality rows; top-left blocks used).
  Eigen::MatrixXd H_, Aeq_, C_;
  Eigen::VectorXd g_, beq_, clo_, cup_, empty_;
  Eigen::Matrix<double, 6, 1> wrench_;
  QpSolver hard_, relaxed_;
  std::array<int, kWheels> slot_{};  // variable block of wheel k, -1 if not in stance
  Forces F_ = Forces::Zero();
  Eigen::VectorXd tau_ff_;
  double residual_ = 0.0;
  int iterations_ = 0;
  ForceDistributionStatus status_ = ForceDistributionStatus::kFailed;
};

}  // namespace centaur
