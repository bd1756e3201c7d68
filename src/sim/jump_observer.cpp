#include "sim/jump_observer.hpp"

#include "sim/compare_pitch.hpp"

#include <algorithm>
#include <cmath>

namespace centaur::sim {

namespace {
constexpr double kRadToDeg = 180.0 / M_PI;
double pitchOf(const Eigen::Quaterniond& q) { return pitchFromQuaternion(q.w(), q.x(), q.y(), q.z()); }  // ZYX
}  // namespace

JumpObserver::JumpObserver(const MujocoRobot& robot, const JumpObserverParams& params) : p_(params) {
  const mjModel* m = robot.model();
  wall_body_ = mj_name2id(m, mjOBJ_BODY, "wall");
  rear_left_ = mj_name2id(m, mjOBJ_BODY, p_.rear_left.c_str());
  rear_right_ = mj_name2id(m, mjOBJ_BODY, p_.rear_right.c_str());
}

void JumpObserver::observe(const MujocoRobot& robot, const RobotState& state, const JointCommand&) {
  const double t = robot.time();
  const Eigen::Vector3d p = robot.basePosition();
  if (first_) {
    z0_ = p.z();
    first_ = false;
  }
  t_last_ = t;
  final_pitch_ = pitchOf(robot.baseOrientation());
  final_height_error_ = p.z() - z0_;
  if (t < p_.primitive_start) return;
  const double imu_pitch = pitchOf(state.imu_quat);
  pitch_sq_sum_ += imu_pitch * imu_pitch;
  ++pitch_samples_;
  peak_imu_pitch_ = std::max(peak_imu_pitch_, std::abs(imu_pitch));
  apex_ = std::max(apex_, p.z());

  // contacts of the robot with anything (ground truth), and of the rear wheels with the wall
  const mjModel* m = robot.model();
  const mjData* d = robot.data();
  bool any = false;
  double wall_l = 0.0, wall_r = 0.0;
  for (int c = 0; c < d->ncon; ++c) {
    const mjContact& con = d->contact[c];
    const int b1 = m->geom_bodyid[con.geom1], b2 = m->geom_bodyid[con.geom2];
    mjtNum f[6];
    mj_contactForce(m, d, c, f);
    const double fn = std::abs(f[0]);
    if (fn > 1.0) any = true;
    if (wall_body_ >= 0 && (b1 == wall_body_ || b2 == wall_body_)) {
      const int other = b1 == wall_body_ ? b2 : b1;
      if (other == rear_left_) wall_l += fn;
      if (other == rear_right_) wall_r += fn;
    }
  }
  if (!any) {
    if (flight_start_ < 0.0) flight_start_ = t;
    flight_best_ = std::max(flight_best_, t - flight_start_);
  } else {
    flight_start_ = -1.0;
  }
  if (wall_l > p_.wall_force_threshold && wall_r > p_.wall_force_threshold) {
    if (wall_start_ < 0.0) wall_start_ = t;
    wall_best_ = std::max(wall_best_, t - wall_start_);
  } else {
    wall_start_ = -1.0;
  }
}

std::map<std::string, double> JumpObserver::summary() const {
  std::map<std::string, double> s;
  s["pitch_rms_deg"] = pitch_samples_ > 0 ? std::sqrt(pitch_sq_sum_ / pitch_samples_) * kRadToDeg : 0.0;
  s["peak_imu_pitch_deg"] = peak_imu_pitch_ * kRadToDeg;
  s["flight_time_s"] = flight_best_;
  s["apex_height_m"] = apex_;
  s["final_pitch_deg"] = final_pitch_ * kRadToDeg;
  s["final_height_error_m"] = final_height_error_;
  if (p_.kind == JumpKind::kHalfSquat) s["wall_contact_s"] = wall_best_;
  return s;
}

std::string JumpObserver::outcome() const {
  if (p_.kind == JumpKind::kHalfSquat) return wall_best_ >= p_.min_wall_contact ? "success" : "no_wall_contact";
  if (flight_best_ < p_.min_flight) return "no_flight";
  if (std::abs(final_pitch_) * kRadToDeg >= p_.max_final_pitch_deg || std::abs(final_height_error_) >= p_.max_height_error)
    return "not_upright";
  return "success";
}

}  // namespace centaur::sim
