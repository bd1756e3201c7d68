#include "sweep/run_record.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "common/error.hpp"

namespace centaur::sweep {

const std::vector<MetricInfo>& metricInfo() {
  static const std::vector<MetricInfo> info = {
      {"peak_pitch_deg", "deg", "max |pitch| of the pelvis over the run (ground truth)", false},
      {"pitch_rms_deg", "deg", "RMS of the IMU pitch from the primitive's start", false},
      {"peak_imu_pitch_deg", "deg", "max |IMU pitch| from the primitive's start", false},
      {"max_torque_ratio", "1", "peak applied |tau| / effort limit (1 = a drive saturated)", false},
      {"wall_contact_s", "s", "longest time both rear wheels press on the wall (half-squat jump; NaN otherwise)",
       false},
      {"flight_time_s", "s", "longest interval without any contact", false},
      {"apex_height_m", "m", "max pelvis height after the primitive's start", false},
      {"final_pitch_deg", "deg", "pelvis pitch at the end", false},
      {"final_height_error_m", "m", "pelvis height at the end minus at the start", false},
      {"fall_time_s", "s", "robot time the fall criterion first held (NaN: no fall)", false},
      {"duration_s", "s", "simulated time", false},
      {"run_time_s", "s", "wall time of the run: setup, simulation (machine-dependent)", true},
      {"real_time_factor", "1", "simulated time / wall time of the control loop (machine-dependent)", true},
  };
  return info;
}

RunRecord::RunRecord() : metrics(metricInfo().size(), std::numeric_limits<double>::quiet_NaN()) {}

double RunRecord::metric(const std::string& name) const {
  const auto& info = metricInfo();
  for (std::size_t i = 0; i < info.size(); ++i) {
    if (name == info[i].name) return metrics[i];
  }
  return std::numeric_limits<double>::quiet_NaN();
}

void RunRecord::set(const std::string& name, double value) {
  const auto& info = metricInfo();
  for (std::size_t i = 0; i < info.size(); ++i) {
    if (name == info[i].name) {
      metrics[i] = value;
      return;
    }
  }
  throw std::invalid_argument("no metric '" + name + "'");
}

nlohmann::json toJson(const RunRecord& r) {
  nlohmann::json j;
  j["run"] = r.run;
  j["outcome"] = r.outcome;
  const auto& info = metricInfo();
  for (std::size_t i = 0; i < info.size(); ++i) {
    j[info[i].name] = std::isfinite(r.metrics[i]) ? nlohmann::json(r.metrics[i]) : nlohmann::json(nullptr);
  }
  if (!r.error.empty()) j["error"] = r.error;
  return j;
}

RunRecord recordFromJson(const nlohmann::json& j, const std::string& where) {
  RunRecord r;
  if (!j.is_object() || !j.contains("run") || !j["run"].is_number_integer() || !j.contains("outcome") ||
      !j["outcome"].is_string()) {
    throw InputError(where + ": not a run record (run, outcome, metrics)");
  }
  r.run = j["run"].get<std::int64_t>();
  r.outcome = j["outcome"].get<std::string>();
  const auto& info = metricInfo();
  for (std::size_t i = 0; i < info.size(); ++i) {
    const auto it = j.find(info[i].name);
    if (it != j.end() && it->is_number()) r.metrics[i] = it->get<double>();
  }
  if (j.contains("error") && j["error"].is_string()) r.error = j["error"].get<std::string>();
  return r;
}

}  // namespace centaur::sweep
