#pragma once
// The plots under the 3D view, synced with the replay (docs/report.md):
//   pitch   IMU pitch [deg] (the paper's Fig. 4) and the planned waist pitch;
//   force   contact force |F| per wheel [N], measured (ground truth, solid) and planned (dashed);
//   torque  applied joint torque / effort limit of the most loaded joints;
//   height  (a plan alone) planned waist height [m].
// Each plot: {"id", "title", "unit", "t": float32 base64, "series": [{"label", "color", "dash", "data": float32
// base64}]}; every series of a plot shares its time axis (robot time, s). A log is plotted at its own rate (one
// row in `stride` when it has more than kMaxPlotSamples rows); a plan's series on the log's rows are the plan's
// sample at that time (held before its start and after its end, as the replay does).
#include <vector>

#include <nlohmann/json.hpp>

#include "data/primitive.hpp"
#include "data/sim_log_file.hpp"
#include "report/kinematic_model.hpp"

namespace centaur::report {

inline constexpr long kMaxPlotSamples = 20000;
inline constexpr int kTorquePlotJoints = 6;

/// Plots of a simulated run; `plan` may be null, `plan_start` is the robot time of its first sample.
nlohmann::json logPlots(const data::SimLogFile& log, const KinematicModel& model, const data::Primitive* plan,
                        double plan_start);

/// Plots of a plan alone (its own clock, t = 0 at its first sample).
nlohmann::json planPlots(const data::Primitive& plan);

}  // namespace centaur::report
