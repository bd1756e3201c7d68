#pragma once
// `centaur report` and the report.html of `centaur compare`: one self-contained HTML page replaying simulated
// runs (and plans) in 3D with synced plots and the runs' metadata (docs/report.md).
#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace centaur::report {

/// One entry of the page's run selector: a simulated run (log, optionally with its plan as a ghost) or a plan
/// alone (no log).
struct RunSource {
  std::string label;           ///< shown in the selector; "" = derived from the file names
  std::string log_path;        ///< simulation log ("centaur-sim-log 1"); "" = a plan alone
  std::string primitive_path;  ///< primitive file; "" = no plan
  std::string primitive_name;  ///< its group; "" = the log's scenario, else the file's only primitive
};

struct ReportOptions {
  std::string title;            ///< "" = derived from the runs
  double pose_rate_hz = 100.0;  ///< [Hz] body poses per second of replay, [10, 1000]
  std::string model_path;       ///< MJCF; "" = the first log's `model` setting, else the shipped CENTAURO
  /// Paths shown in the page instead of the ones read (a file read from a staging directory under the name it
  /// will have once committed, e.g. by `compare`); a path not in the map is shown as it is.
  std::map<std::string, std::string> shown_paths;
};

struct ReportStats {
  std::size_t bytes = 0;   ///< size of the page
  std::size_t runs = 0;
  std::size_t frames = 0;  ///< body-pose frames over all runs
};

/// Every source of a page, in run-selector order: each log of `logs` (with the plan of `primitive_path` when
/// given), or, without logs, every primitive of `primitive_path` (the one named `primitive_name` if not "").
std::vector<RunSource> runSources(const std::vector<std::string>& logs, const std::string& primitive_path,
                                  const std::string& primitive_name);

/// Reads every source, builds the page and writes it to `html_path` atomically (temporary file, then rename).
/// Bad input (a file that is not a log or a primitive file, a dataset of the wrong shape, a log whose joints
/// are not the model's, an empty run list, a rate out of range) throws InputError naming the file and the
/// dataset before anything is written; I/O failures RuntimeError.
ReportStats writeReport(const std::string& html_path, const std::vector<RunSource>& runs,
                        const ReportOptions& options);

}  // namespace centaur::report
