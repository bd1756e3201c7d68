#pragma once
// Replay of a lower-body primitive: the planner's 1 kHz samples turned into the references
// of the whole-body controller at any time t since the primitive's start.
//
//   b_p_wheel   pelvis -> wheel-centre positions r_C (the template's point foot is the wheel centre and the
//               template's waist frame is the pelvis frame; foot order = the robot's wheel order FL, FR, RL, RR),
//   b_v_wheel   their time derivatives (base frame),
//   F_d         planned contact forces on the wheels (W),
//   contact     planned contact flags,
//   normal      the unit normal (W) of the surface each wheel is planned on: +z for the ground, +x for the
//               wall of a half-squat jump. It is derived once, at construction, from where the foot is
//               during each contact interval (ground: foot z = ground_z + wheel_radius; wall: foot x =
//               wall_x + wheel_radius), so it is known before touch-down too (the next contact's surface),
//   vdot_base   planned base acceleration in the RobotModel's layout [w_a (W), b_alpha (base frame)], from the
//               OCP's piecewise-constant control nu_dot (exact, no differentiation of samples).
// Before t = 0 the first sample is held, after the end the last one (with zero velocity and acceleration).
//
// Model/Data split: the constructor copies what it needs (allocates, throws InputError for a primitive it
// cannot replay); sample() never allocates nor throws.
#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "data/primitive.hpp"

namespace centaur {

struct ReplaySample {
  Eigen::Matrix<double, 3, 4> b_p_wheel = Eigen::Matrix<double, 3, 4>::Zero();  ///< [m] base frame
  Eigen::Matrix<double, 3, 4> b_v_wheel = Eigen::Matrix<double, 3, 4>::Zero();  ///< [m/s] base frame
  Eigen::Matrix<double, 3, 4> w_F = Eigen::Matrix<double, 3, 4>::Zero();        ///< [N] on the wheels, W
  std::array<bool, 4> contact = {true, true, true, true};                       ///< planned contact
  std::array<Eigen::Vector3d, 4> w_normal;                                       ///< surface normal (W)
  Eigen::Matrix<double, 6, 1> vdot_base = Eigen::Matrix<double, 6, 1>::Zero();  ///< [w_a; b_alpha]
  Eigen::Vector3d w_p_base = Eigen::Vector3d::Zero();                            ///< [m] planned waist position
  Eigen::Vector4d base_quat_wxyz = Eigen::Vector4d(1, 0, 0, 0);                  ///< planned W_R_B (w,x,y,z)
  long index = 0;                                                                ///< sample used
  bool running = false;                                                          ///< 0 <= t < duration
};

class PrimitiveReplay {
 public:
  /// Throws InputError naming the primitive if a dataset is missing or has the wrong shape.
  explicit PrimitiveReplay(const data::Primitive& primitive);

  /// The references at time t [s] since the primitive's start (nearest 1 kHz sample at or before t).
  void sample(double t, ReplaySample& out) const noexcept;

  double duration() const { return duration_; }   ///< [s] time of the last sample
  double sampleDt() const { return dt_; }         ///< [s]
  const std::string& name() const { return name_; }
  /// Surface normal of wheel k during its contact interval that contains (or follows) sample i (W).
  const Eigen::Vector3d& normalAt(long i, int k) const { return normals_[static_cast<std::size_t>(i)][k]; }
  /// Times [s] of the planned lift-offs and touch-downs of wheel k.
  const std::vector<double>& liftOffs(int k) const { return lift_offs_[k]; }
  const std::vector<double>& touchDowns(int k) const { return touch_downs_[k]; }

 private:
  std::string name_;
  double dt_ = 0.001, duration_ = 0.0;
  long n_ = 0;
  data::RowMatrix foot_rel_, foot_vel_rel_, force_, contact_, base_pos_, base_quat_;
  Eigen::VectorXd knot_t_;
  data::RowMatrix knot_u_;
  std::vector<std::array<Eigen::Vector3d, 4>> normals_;
  std::array<std::vector<double>, 4> lift_offs_, touch_downs_;
};

}  // namespace centaur
