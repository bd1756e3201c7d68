#pragma once
// The comparison table of `centaur compare` (jumps x stabilizer modes): one row per run, written as a
// markdown table (compare.md), a JSON array (compare.json; field names as in `centaur simulate --json`) and the
// IMU pitch histories as one CSV (compare-pitch.csv, the data of compare-pitch.png).
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>  // header-only (Debian nlohmann-json3-dev)

#include "sim/compare_pitch.hpp"
#include "sim/compare_runner.hpp"

namespace centaur::sim {

/// One run of the comparison. Absent numbers (a run that failed; wall contact of a squat jump) are nullopt
/// and appear as "-" in markdown and null in JSON.
struct CompareRow {
  std::string scenario;    ///< the jump, e.g. "squat-jump"
  std::string stabilizer;  ///< the mode: none | raibert | angmom | ocp
  std::string outcome;     ///< the run's outcome ("success", "fall", "no_wall_contact", ...), or "error"
  std::optional<double> peak_pitch_deg;    ///< [deg] max |pitch| of the pelvis (ground truth, runner)
  std::optional<double> pitch_rms_deg;     ///< [deg] RMS pitch (scenario observer)
  std::optional<double> max_torque_ratio;  ///< [-] peak |tau| / effort limit (runner)
  std::optional<double> wall_contact_s;    ///< [s] steady rear-wheel wall contact (half-squat jump observer)
  std::optional<double> real_time_factor;  ///< simulated time / wall time of the loop
  std::optional<double> wall_time_s;       ///< [s] wall time of the loop
  std::optional<double> duration_s;        ///< [s] simulated time
  std::optional<double> fall_time_s;       ///< [s] first time the fall criterion held (absent: never)
  std::map<std::string, double> extra;     ///< every number of the scenario observer (RunSummary::extra)
  std::string log;                         ///< the run's HDF5 log ("" = none)
  std::string error;                       ///< why the run failed ("" = it completed)
};

/// The row of a finished batch run (summary fields, plus pitch_rms_deg and wall_contact_s from the
/// observer's extra numbers when present).
CompareRow makeCompareRow(const std::string& scenario, const std::string& stabilizer, const BatchResult& result,
                          const std::string& log_path);

/// Markdown table: jump | mode | outcome | peak pitch [deg] | pitch RMS [deg] | max torque ratio |
/// wall contact [s] | real-time factor, then one line per failed run with its message.
std::string compareMarkdown(const std::vector<CompareRow>& rows);

/// One JSON object per row: scenario, stabilizer, outcome, peak_pitch_deg, pitch_rms_deg, max_torque_ratio,
/// wall_contact_s, real_time_factor, wall_time_s, duration_s, fall_time_s (null if absent), log, error (only
/// for failed runs), then the observer's other numbers under their own names (as in `simulate --json`).
nlohmann::json compareJson(const std::vector<CompareRow>& rows);

/// CSV of pitch histories on a common time axis: header "t_s,<name 1>,<name 2>,...", one row per distinct
/// sample time (times equal to 1 ns are merged), "nan" where a series has no sample at that time (e.g. a run
/// that stopped early after a fall). names.size() must equal series.size().
std::string pitchCsv(const std::vector<std::string>& names, const std::vector<PitchSeries>& series);

}  // namespace centaur::sim
