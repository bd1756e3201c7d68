#pragma once
// Outcome and metrics of a jump run, from the simulator's ground truth and the IMU the
// controller saw. Added to the run summary / `--json`:
//   pitch_rms_deg        RMS of the IMU pitch (ZYX pitch of w_R_imu) from the primitive's start to the end
//   peak_imu_pitch_deg   max |IMU pitch| over the same window
//   flight_time_s        longest interval with no wheel touching anything (ground truth contact forces < 1 N)
//   apex_height_m        max pelvis height after the primitive's start
//   final_pitch_deg      pelvis pitch at the end (ground truth)
//   final_height_error_m pelvis height at the end minus at the start
//   wall_contact_s       (half-squat jump) longest interval in which BOTH rear wheels press on the wall
//                        (normal force of their contacts with the wall geom > wall_force_threshold)
// Outcome (replaces the runner's "success" unless the runner saw a fall):
//   squat-jump:      "success" iff it flew (flight_time >= 0.05 s), and at the end |pitch| < 10 deg and
//                    |height error| < 5 cm; otherwise "no_flight" or "not_upright".
//   half-squat-jump: "success" iff wall_contact_s >= 0.5 s; otherwise "no_wall_contact".
#include <string>

#include "sim/scenario.hpp"

namespace centaur::sim {

enum class JumpKind { kSquat, kHalfSquat };

struct JumpObserverParams {
  JumpKind kind = JumpKind::kSquat;
  double primitive_start = 0.5;        ///< [s] robot time at which the primitive starts
  double wall_force_threshold = 5.0;   ///< [N]
  double min_wall_contact = 0.5;       ///< [s]
  double min_flight = 0.05;            ///< [s]
  double max_final_pitch_deg = 10.0;   ///< [deg]
  double max_height_error = 0.05;      ///< [m]
  std::string rear_left = "wheel_3", rear_right = "wheel_4";  ///< the rear feet's contact bodies (RL, RR)
};

class JumpObserver final : public RunObserver {
 public:
  /// Resolves the wall geom (if any) and the rear wheel bodies in the robot's model.
  JumpObserver(const MujocoRobot& robot, const JumpObserverParams& params);
  void observe(const MujocoRobot& robot, const RobotState& state, const JointCommand& command) override;
  std::map<std::string, double> summary() const override;
  std::string outcome() const override;

 private:
  JumpObserverParams p_;
  int wall_body_ = -1, rear_left_ = -1, rear_right_ = -1;
  bool first_ = true;
  double z0_ = 0.0, t_last_ = 0.0;
  double pitch_sq_sum_ = 0.0, peak_imu_pitch_ = 0.0, apex_ = 0.0;
  long pitch_samples_ = 0;
  double flight_start_ = -1.0, flight_best_ = 0.0;
  double wall_start_ = -1.0, wall_best_ = 0.0;
  double final_pitch_ = 0.0, final_height_error_ = 0.0;
};

}  // namespace centaur::sim
