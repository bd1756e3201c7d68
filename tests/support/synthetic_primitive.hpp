#pragma once
// A synthetic, analytic forward jump used by the primitive I/O, summary and plot tests.
//
//   [0, 0.29)    all four feet on the ground; the waist accelerates up (a_z = g/2) and forward (a_x = 1 m/s^2)
//   [0.29, 0.30) front feet (FL, FR) lifted; the rear feet carry the whole load
//   [0.30, 0.60) flight: ballistic waist; vertical take-off speed g * 0.15 so the flight lasts 0.3 s and
//                the waist lands at its take-off height; apex at t = 0.45
//   [0.60, 1.00] all feet on the ground; the waist decelerates to rest
// Samples every 1 ms (1001 samples); feet are wheel centres (z = wheel radius on the ground); the waist
// pitches by 0.05 sin(pi t) so that foot_pos_rel differs from foot_pos - base_pos.
#include <Eigen/Geometry>

#include <cmath>
#include <string>

#include "data/primitive.hpp"

namespace centaur::test {

struct SyntheticJump {
  static constexpr double g = 9.81;
  static constexpr double mass = 93.1;
  static constexpr double z0 = 0.60;            // initial waist height [m]
  static constexpr double wheel_radius = 0.124;
  static constexpr double az = g / 2.0;         // upward acceleration in the push-off [m/s^2]
  static constexpr double ax = 1.0;             // forward acceleration in the push-off [m/s^2]
  static constexpr double t_front_lift = 0.29;  // index 290
  static constexpr double t_take_off = 0.30;    // index 300
  static constexpr double t_land = 0.60;        // index 600
  static constexpr double t_end = 1.00;         // index 1000
  static double vz() { return az * t_take_off; }   // take-off vertical speed = g * 0.15
  static double vx() { return ax * t_take_off; }
  static double zTakeOff() { return z0 + 0.5 * az * t_take_off * t_take_off; }
  static double apexGain() { return zTakeOff() - z0 + vz() * vz() / (2.0 * g); }
  static double apexTime() { return t_take_off + vz() / g; }
  static double pushForceZPerFoot() { return mass * (g + az) / 4.0; }  // all four feet share the load
};

/// The synthetic jump; `offset` shifts every position in x (to tell two primitives apart).
inline data::Primitive makeSyntheticJump(const std::string& name, double offset = 0.0) {
  using J = SyntheticJump;
  constexpr int n = 1001;
  data::Primitive p;
  p.name = name;
  p.t.resize(n);
  p.q.resize(n, 19);
  p.nu.resize(n, 18);
  p.base_pos.resize(n, 3);
  p.base_quat.resize(n, 4);
  p.base_vel.resize(n, 3);
  p.base_omega.resize(n, 3);
  p.foot_pos.resize(n, 12);
  p.foot_pos_rel.resize(n, 12);
  p.foot_vel_rel.resize(n, 12);
  p.force.resize(n, 12);
  p.contact.resize(n, 4);
  p.tau.resize(n, 12);

  const double hip_x[4] = {0.35, 0.35, -0.35, -0.35};
  const double hip_y[4] = {0.35, -0.35, 0.35, -0.35};
  const double t_land_brake = J::t_end - J::t_land;
  const double brake_z = J::vz() / t_land_brake;  // deceleration after landing (vertical speed -vz -> 0)
  const double brake_x = J::vx() / t_land_brake;
  const double x_take = offset + 0.5 * J::ax * J::t_take_off * J::t_take_off;
  const double x_land = x_take + J::vx() * (J::t_land - J::t_take_off);
  const double step = x_land - offset;  // the feet land where they stood relative to the waist

  for (int i = 0; i < n; ++i) {
    const double t = 0.001 * i;
    p.t(i) = t;
    // ---- waist -----------------------------------------------------------------------------------
    double x, z, vx, vz, ax_, az_;
    if (i < 300) {
      x = offset + 0.5 * J::ax * t * t, vx = J::ax * t, ax_ = J::ax;
      z = J::z0 + 0.5 * J::az * t * t, vz = J::az * t, az_ = J::az;
    } else if (i < 600) {
      const double s = t - J::t_take_off;
      x = x_take + J::vx() * s, vx = J::vx(), ax_ = 0.0;
      z = J::zTakeOff() + J::vz() * s - 0.5 * J::g * s * s, vz = J::vz() - J::g * s, az_ = -J::g;
    } else {
      const double s = t - J::t_land;
      x = x_land + J::vx() * s - 0.5 * brake_x * s * s, vx = J::vx() - brake_x * s, ax_ = -brake_x;
      z = J::zTakeOff() - J::vz() * s + 0.5 * brake_z * s * s, vz = -J::vz() + brake_z * s, az_ = brake_z;
    }
    const double pitch = 0.05 * std::sin(M_PI * t);
    const double pitch_rate = 0.05 * M_PI * std::cos(M_PI * t);
    const Eigen::Quaterniond quat(Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()));
    const Eigen::Vector3d base(x, 0.0, z);
    p.base_pos.row(i) << base.x(), base.y(), base.z();
    p.base_quat.row(i) << quat.w(), quat.x(), quat.y(), quat.z();
    p.base_vel.row(i) << vx, 0.0, vz;
    p.base_omega.row(i) << 0.0, pitch_rate, 0.0;

    // ---- feet ------------------------------------------------------------------------------------
    int loaded = 0;
    for (int f = 0; f < 4; ++f) {
      const bool front = f < 2;
      const int lift = front ? 290 : 300;
      const bool stance = i < lift || i >= 600;
      p.contact(i, f) = stance ? 1.0 : 0.0;
      if (stance && i < 300) ++loaded;
      Eigen::Vector3d foot(offset + hip_x[f], hip_y[f], J::wheel_radius);
      if (i >= 600) {
        foot.x() += step;
      } else if (i >= lift) {
        const double s = (i - lift) / double(600 - lift);
        foot.x() += step * s;
        foot.z() += 0.4 * s * (1.0 - s);  // swing bump, 10 cm at mid-swing
      }
      p.foot_pos.block<1, 3>(i, 3 * f) = foot.transpose();
      p.foot_pos_rel.block<1, 3>(i, 3 * f) = (quat.conjugate() * (foot - base)).transpose();
    }
    // ---- forces: the loaded feet share m (a + g); tau = -(force in the waist frame) -----------------
    const Eigen::Vector3d total = J::mass * Eigen::Vector3d(ax_, 0.0, az_ + J::g);
    const int share = i < 300 ? loaded : (i >= 600 ? 4 : 0);
    for (int f = 0; f < 4; ++f) {
      const Eigen::Vector3d force =
          (share > 0 && p.contact(i, f) > 0.5) ? Eigen::Vector3d(total / share) : Eigen::Vector3d::Zero();
      p.force.block<1, 3>(i, 3 * f) = force.transpose();
      p.tau.block<1, 3>(i, 3 * f) = -(quat.conjugate() * force).transpose();
    }
  }
  // foot velocities in B by central differences; q and nu assembled from the parts
  for (int i = 0; i < n; ++i) {
    const int a = std::max(0, i - 1), b = std::min(n - 1, i + 1);
    p.foot_vel_rel.row(i) = (p.foot_pos_rel.row(b) - p.foot_pos_rel.row(a)) / (p.t(b) - p.t(a));
    p.q.row(i) << p.base_pos.row(i), p.base_quat.row(i), p.foot_pos_rel.row(i);
    p.nu.row(i) << p.base_vel.row(i), p.base_omega.row(i), p.foot_vel_rel.row(i);
  }

  // knots: 10 intervals of 0.1 s
  p.knot_t = Eigen::VectorXd::LinSpaced(11, 0.0, 1.0);
  p.knot_x.resize(11, 37);
  for (int k = 0; k <= 10; ++k) p.knot_x.row(k) << p.q.row(100 * k), p.nu.row(100 * k);
  p.knot_u.resize(10, 31);
  for (int k = 0; k < 10; ++k) {
    for (int c = 0; c < 31; ++c) p.knot_u(k, c) = std::sin(0.37 * k + 1.3 * c);
  }
  p.knot_u.col(30).setConstant(0.1);
  p.knot_dt = Eigen::VectorXd::Constant(10, 0.1);

  p.solve.status = "solved";
  p.solve.iterations = 42;
  p.solve.solve_time_s = 0.1234;
  p.solve.cost = 1.5e3;
  p.solve.backend = "riccati";
  p.solve.max_constraint_violation = 3.2e-9;
  p.config_yaml = "primitive: squat-jump\nmodel:\n  preset: centauro   # 93.1 kg\n  waist_mass: 69.0\n";
  p.scalars = {{"total_mass", J::mass}, {"waist_mass", 69.0}, {"g", J::g}};
  p.vectors = {{"waist_com", {0.16, 0.0, 0.0}},
               {"waist_inertia", {1.2, 0.0, 0.01, 0.0, 2.3, 0.0, 0.01, 0.0, 2.9}},
               {"hip_offset_x", {0.35, 0.35, -0.35, -0.35}},
               {"one", {7.0}}};
  p.strings = {{"model_preset", "centauro"}, {"foot_names", "wheel_1,wheel_2,wheel_3,wheel_4"}};
  return p;
}

}  // namespace centaur::test
