#include "report/run_plots.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "report/channel_codec.hpp"
#include "report/plan_ghost.hpp"

namespace centaur::report {

namespace {

constexpr double kRadToDeg = 180.0 / M_PI;
const char* const kWheelColors[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728"};
const char* const kFootNames[] = {"FL", "FR", "RL", "RR"};
const char* const kJointColors[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b"};

nlohmann::json series(const std::string& label, const std::string& color, bool dash, const std::vector<double>& v) {
  return {{"label", label}, {"color", color}, {"dash", dash}, {"data", encodeFloat32(v)}};
}

nlohmann::json plot(const char* id, const char* title, const char* unit, const std::vector<double>& t,
                    nlohmann::json list) {
  return {{"id", id}, {"title", title}, {"unit", unit}, {"t", encodeFloat32(t)}, {"series", std::move(list)}};
}

double norm3(const double* f) { return std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]); }

/// Planned force magnitude of foot k and waist pitch at each time of `t`.
void plannedOn(const data::Primitive& plan, double start, const std::vector<double>& t,
               std::vector<std::vector<double>>& force, std::vector<double>& pitch) {
  force.assign(4, {});
  pitch.clear();
  for (const double ti : t) {
    const Eigen::Index i = planRow(plan, start, ti);
    for (int k = 0; k < 4; ++k) force[k].push_back(norm3(plan.force.row(i).data() + 3 * k));
    pitch.push_back(kRadToDeg * pitchOf(plan.base_quat(i, 0), plan.base_quat(i, 1), plan.base_quat(i, 2),
                                        plan.base_quat(i, 3)));
  }
}

/// The kTorquePlotJoints joints with the largest peak |tau_applied| / effort limit, their ratio series.
nlohmann::json torquePlot(const data::SimLogFile& log, const KinematicModel& model, const std::vector<Eigen::Index>& rows,
                          const std::vector<double>& t) {
  const std::vector<std::string>& names = log.header().joint_names;
  const std::vector<double> limit = model.effortLimits(names);
  const data::RowMatrix tau = log.read("tau_applied");
  std::vector<double> peak(names.size(), 0.0);
  for (Eigen::Index i = 0; i < tau.rows(); ++i) {
    for (std::size_t j = 0; j < names.size(); ++j) {
      if (std::isfinite(limit[j]) && limit[j] > 0.0) peak[j] = std::max(peak[j], std::abs(tau(i, j)) / limit[j]);
    }
  }
  std::vector<std::size_t> order(names.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return peak[a] > peak[b]; });
  nlohmann::json list = nlohmann::json::array();
  for (std::size_t r = 0; r < order.size() && r < static_cast<std::size_t>(kTorquePlotJoints); ++r) {
    const std::size_t j = order[r];
    if (peak[j] <= 0.0) break;
    std::vector<double> v;
    for (const Eigen::Index i : rows) v.push_back(tau(i, static_cast<Eigen::Index>(j)) / limit[j]);
    list.push_back(series(names[j], kJointColors[r], false, v));
  }
  return plot("torque", "Joint torque / effort limit (most loaded joints)", "-", t, std::move(list));
}

}  // namespace

nlohmann::json logPlots(const data::SimLogFile& log, const KinematicModel& model, const data::Primitive* plan,
                        double plan_start) {
  const Eigen::VectorXd time = log.time();
  const Eigen::Index n = time.size();
  const Eigen::Index stride = std::max<Eigen::Index>(1, (n + kMaxPlotSamples - 1) / kMaxPlotSamples);
  std::vector<Eigen::Index> rows;
  std::vector<double> t;
  for (Eigen::Index i = 0; i < n; i += stride) {
    rows.push_back(i);
    t.push_back(time[i]);
  }
  const data::RowMatrix imu = log.read("imu_quat"), wheel_force = log.read("wheel_force");
  std::vector<double> pitch;
  for (const Eigen::Index i : rows) pitch.push_back(kRadToDeg * pitchOf(imu(i, 0), imu(i, 1), imu(i, 2), imu(i, 3)));
  nlohmann::json pitch_series = nlohmann::json::array({series("IMU pitch", "#1f3b73", false, pitch)});
  nlohmann::json force_series = nlohmann::json::array();
  const std::vector<std::string>& bodies = log.header().contact_bodies;
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    std::vector<double> f;
    for (const Eigen::Index i : rows) f.push_back(norm3(wheel_force.row(i).data() + 3 * k));
    const std::string label = (k < 4 ? std::string(kFootNames[k]) + " " : std::string()) + bodies[k];
    force_series.push_back(series(label, kWheelColors[k % 4], false, f));
  }
  if (plan != nullptr) {
    std::vector<std::vector<double>> planned_force;
    std::vector<double> planned_pitch;
    plannedOn(*plan, plan_start, t, planned_force, planned_pitch);
    pitch_series.push_back(series("planned waist pitch", "#888888", true, planned_pitch));
    for (int k = 0; k < 4; ++k) {
      force_series.push_back(series(std::string(kFootNames[k]) + " planned", kWheelColors[k], true, planned_force[k]));
    }
  }
  return nlohmann::json::array({plot("pitch", "IMU pitch (positive: nose down)", "deg", t, std::move(pitch_series)),
                                plot("force", "Contact force per wheel |F|: measured (solid), planned (dashed)", "N",
                                     t, std::move(force_series)),
                                torquePlot(log, model, rows, t)});
}

nlohmann::json planPlots(const data::Primitive& plan) {
  const std::vector<double> t(plan.t.data(), plan.t.data() + plan.t.size());
  std::vector<std::vector<double>> force;
  std::vector<double> pitch, height;
  plannedOn(plan, 0.0, t, force, pitch);
  for (Eigen::Index i = 0; i < plan.samples(); ++i) height.push_back(plan.base_pos(i, 2));
  nlohmann::json force_series = nlohmann::json::array();
  for (int k = 0; k < 4; ++k) force_series.push_back(series(std::string(kFootNames[k]) + " planned", kWheelColors[k], true, force[k]));
  return nlohmann::json::array(
      {plot("pitch", "Planned waist pitch (positive: nose down)", "deg", t,
            nlohmann::json::array({series("planned waist pitch", "#888888", true, pitch)})),
       plot("force", "Planned contact force per foot |F|", "N", t, std::move(force_series)),
       plot("height", "Planned waist height", "m", t,
            nlohmann::json::array({series("waist z", "#1f3b73", false, height)}))});
}

}  // namespace centaur::report
