#pragma once
// The numbers of a run shown in the page's metadata panel: outcome, peak pitch, pitch RMS, max torque ratio,
// wall contact, flight time, apex, fall time, duration. They come from the log's `summary` attribute (written by
// the simulator, the same numbers as `centaur simulate --json`); a log without one (written before it existed)
// gets the ones that the log's datasets determine: peak pelvis pitch, IMU pitch RMS from the primitive's start
// and max |tau_applied| / effort limit, and outcome "not recorded".
#include <nlohmann/json.hpp>

#include "data/sim_log_file.hpp"
#include "report/kinematic_model.hpp"

namespace centaur::report {

/// [{"key", "label", "value" (number, string or null), "unit"}], in display order; plus "source":
/// "simulator" or "log". InputError naming the log and `summary` if that attribute is not a JSON object.
nlohmann::json logMetrics(const data::SimLogFile& log, const KinematicModel& model, double primitive_start);

}  // namespace centaur::report
