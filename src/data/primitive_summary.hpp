#pragma once
// Key numbers of a primitive (phase times, flight, apex, peak forces and torques), computed from its 1 kHz
// samples. Used by `centaur inspect` and by tests.
//
// Time resolution is the sample period. A contact interval [start, end) starts at the first sample in
// contact and ends at the first sample out of contact (or at the last sample time if it lasts to the end),
// so lift-off = end of a stance interval and touch-down = start of the next one. Times absent from the
// motion (no flight phase, a foot that never lifts) are NaN.
#include <array>
#include <string>
#include <vector>

#include "data/primitive.hpp"

namespace centaur::data {

struct TimeInterval {
  double start = 0.0;  ///< [s]
  double end = 0.0;    ///< [s]
  double duration() const { return end - start; }
};

struct FootSummary {
  std::string name;                    ///< FL, FR, RL, RR
  std::vector<TimeInterval> stance;    ///< contact intervals
  std::vector<TimeInterval> swing;     ///< intervals out of contact
  double stance_time = 0.0;            ///< [s] total time in contact
  double lift_off_time = 0.0;          ///< [s] end of the first stance interval that is followed by a swing (NaN if none)
  double touch_down_time = 0.0;        ///< [s] first start of contact after lift-off (NaN if none)
  double peak_force_norm = 0.0;        ///< [N] max |F|
  double peak_force_norm_time = 0.0;   ///< [s]
  double peak_force_z = 0.0;           ///< [N] max F_z (world)
  double peak_force_z_time = 0.0;      ///< [s]
};

struct PrimitiveSummary {
  std::string name;
  Eigen::Index samples = 0;
  double duration = 0.0;        ///< [s] t(last) - t(0)
  int shooting_intervals = 0;   ///< N_s (knots)

  std::array<FootSummary, 4> feet;

  std::vector<TimeInterval> flight;  ///< intervals with all four feet off
  double flight_time = 0.0;          ///< [s] total
  double take_off_time = 0.0;        ///< [s] start of the first flight phase (NaN if none)
  double touch_down_time = 0.0;      ///< [s] end of the first flight phase (NaN if none or if it never ends)

  double start_height = 0.0;  ///< [m] base z at t(0)
  double apex_height = 0.0;   ///< [m] max base z
  double apex_time = 0.0;     ///< [s]
  double apex_gain = 0.0;     ///< [m] apex_height - start_height
  double end_height = 0.0;    ///< [m] base z at the last sample

  double peak_abs_tau = 0.0;       ///< [N] max |tau| over all joints and samples
  int peak_abs_tau_joint = -1;     ///< column of tau (foot-major FL,FR,RL,RR x,y,z)
  double peak_abs_tau_time = 0.0;  ///< [s]

  SolveInfo solve;
};

/// Foot names in storage order.
inline const std::array<const char*, 4> kFootNames = {"FL", "FR", "RL", "RR"};

/// Summary of `p`; throws std::invalid_argument if its arrays are inconsistent with t.
PrimitiveSummary summarize(const Primitive& p);

/// Maximal runs of `flags[i] == value` as time intervals over `t` (same length).
std::vector<TimeInterval> intervalsWhere(const Eigen::VectorXd& t, const std::vector<bool>& flags, bool value);

}  // namespace centaur::data
