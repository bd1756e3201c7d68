#include "report/run_metrics.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"
#include "report/plan_ghost.hpp"

namespace centaur::report {

namespace {

constexpr double kRadToDeg = 180.0 / M_PI;

struct Item {
  const char* key;
  const char* label;
  const char* unit;
};

// Display order; an item the summary lacks is left out (e.g. wall contact of a squat jump).
const Item kItems[] = {
    {"outcome", "outcome", ""},
    {"peak_pitch_deg", "peak pitch (pelvis)", "deg"},
    {"pitch_rms_deg", "pitch RMS (IMU, from the primitive's start)", "deg"},
    {"max_torque_ratio", "max torque ratio (|tau| / effort limit)", ""},
    {"wall_contact_s", "wall contact (both rear wheels)", "s"},
    {"flight_time_s", "flight time", "s"},
    {"apex_height_m", "apex pelvis height", "m"},
    {"fall_time_s", "fall time", "s"},
    {"final_pitch_deg", "final pitch", "deg"},
    {"duration_s", "simulated time", "s"},
};

/// The numbers the log's datasets determine (for logs without a summary).
nlohmann::json computed(const data::SimLogFile& log, const KinematicModel& model, double primitive_start) {
  const Eigen::VectorXd t = log.time();
  const data::RowMatrix base = log.read("base_quat"), imu = log.read("imu_quat"), tau = log.read("tau_applied");
  const std::vector<double> limit = model.effortLimits(log.header().joint_names);
  double peak = 0.0, sq = 0.0, ratio = 0.0;
  long count = 0;
  for (Eigen::Index i = 0; i < t.size(); ++i) {
    peak = std::max(peak, std::abs(pitchOf(base(i, 0), base(i, 1), base(i, 2), base(i, 3))));
    if (t[i] >= primitive_start) {
      const double p = pitchOf(imu(i, 0), imu(i, 1), imu(i, 2), imu(i, 3));
      sq += p * p;
      ++count;
    }
    for (Eigen::Index j = 0; j < tau.cols(); ++j) {
      const double l = limit[static_cast<std::size_t>(j)];
      if (std::isfinite(l) && l > 0.0) ratio = std::max(ratio, std::abs(tau(i, j)) / l);
    }
  }
  nlohmann::json j;
  j["outcome"] = "not recorded (log without summary)";
  j["peak_pitch_deg"] = kRadToDeg * peak;
  j["pitch_rms_deg"] = count > 0 ? kRadToDeg * std::sqrt(sq / static_cast<double>(count)) : 0.0;
  j["max_torque_ratio"] = ratio;
  j["duration_s"] = t.size() > 0 ? t[t.size() - 1] - t[0] : 0.0;
  return j;
}

}  // namespace

nlohmann::json logMetrics(const data::SimLogFile& log, const KinematicModel& model, double primitive_start) {
  nlohmann::json values;
  const std::string& summary = log.header().summary_json;
  const bool recorded = !summary.empty();
  if (recorded) {
    values = nlohmann::json::parse(summary, nullptr, false);
    if (!values.is_object()) throw InputError(log.path(), "summary", "attribute is not a JSON object");
  } else {
    values = computed(log, model, primitive_start);
  }
  nlohmann::json items = nlohmann::json::array();
  for (const Item& it : kItems) {
    if (!values.contains(it.key)) continue;
    items.push_back({{"key", it.key}, {"label", it.label}, {"value", values[it.key]}, {"unit", it.unit}});
  }
  return {{"source", recorded ? "simulator" : "log"}, {"items", items}};
}

}  // namespace centaur::report
