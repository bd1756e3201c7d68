#pragma once
// What one run of a sweep produced: its outcome and metrics (the jump observer's, docs/jumps.md) and its wall
// time. The same JSON form goes into the journal (one line per run) and over MPI from a worker rank to rank 0;
// numbers round-trip exactly (NaN travels as null).
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace centaur::sweep {

/// The metrics of a run, in their column order; `unit`, `description` for the results schema.
struct MetricInfo {
  const char* name;
  const char* unit;
  const char* description;
  bool wall_clock;  ///< depends on the machine (excluded when results of two sweeps are compared)
};
const std::vector<MetricInfo>& metricInfo();

/// Outcomes besides the jump observer's (success, fall, no_flight, not_upright, no_wall_contact):
inline constexpr const char* kOutcomeError = "error";              ///< the run threw (message in `error`)
inline constexpr const char* kOutcomeNotPlanned = "not_planned";   ///< its grid point's plan did not converge

struct RunRecord {
  std::int64_t run = -1;
  std::string outcome;
  std::vector<double> metrics;  ///< metricInfo() order; NaN where not applicable
  std::string error;            ///< the exception's message for outcome "error"

  RunRecord();
  bool success() const { return outcome == "success"; }
  /// Ran to its end (an outcome of the jump, not an error or an unplanned point).
  bool simulated() const { return outcome != kOutcomeError && outcome != kOutcomeNotPlanned; }
  double metric(const std::string& name) const;
  /// Sets metric `name` (std::invalid_argument if there is no such metric).
  void set(const std::string& name, double value);
};

nlohmann::json toJson(const RunRecord& r);
/// InputError (with `where` in the message) if `j` is not a record.
RunRecord recordFromJson(const nlohmann::json& j, const std::string& where);

}  // namespace centaur::sweep
