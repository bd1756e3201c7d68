#include "report/report.hpp"

#include <algorithm>
#include <filesystem>
#include <memory>
#include <optional>

#include <nlohmann/json.hpp>

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "data/primitive_io.hpp"
#include "data/sim_log_file.hpp"
#include "model/chain_from_mjcf.hpp"
#include "report/html_page.hpp"
#include "report/kinematic_model.hpp"
#include "report/log_settings.hpp"
#include "report/plan_ghost.hpp"
#include "report/run_frames.hpp"
#include "report/run_metrics.hpp"
#include "report/run_plots.hpp"
#include "report/scene_geometry.hpp"
#include "report/viewer_asset.hpp"

namespace centaur::report {

namespace {

namespace fs = std::filesystem;

std::string stem(const std::string& path) { return fs::path(path).stem().string(); }

std::string joinNames(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s.empty() ? "none" : s;
}

/// The plan of a source: the group named `name`, else the one named like `scenario`, else the file's only one.
std::optional<data::Primitive> loadPlan(const std::string& file, const std::string& name, const std::string& scenario) {
  if (file.empty()) return std::nullopt;
  std::string group = name;
  if (group.empty()) {
    const std::vector<std::string> names = data::listPrimitives(file);
    if (std::find(names.begin(), names.end(), scenario) != names.end()) {
      group = scenario;
    } else if (names.size() == 1) {
      group = names.front();
    } else {
      throw InputError(file, scenario.empty() ? std::string("<primitive>") : scenario,
                       "no primitive named like the log's scenario; the file holds: " + joinNames(names) +
                           " (choose one with --primitive-name)");
    }
  }
  data::Primitive p = data::readPrimitive(file, group);
  if (p.samples() == 0) throw InputError(file, group + "/t", "the primitive has no samples");
  return p;
}

/// `path` as the page shows it (ReportOptions::shown_paths).
std::string shown(const ReportOptions& options, const std::string& path) {
  const auto it = options.shown_paths.find(path);
  return it == options.shown_paths.end() ? path : it->second;
}

nlohmann::json logRun(const RunSource& src, const data::SimLogFile& log, KinematicModel& model,
                      const ReportOptions& options) {
  const double rate = options.pose_rate_hz;
  const LogSettings settings = readLogSettings(log);
  const std::optional<data::Primitive> plan = loadPlan(src.primitive_path, src.primitive_name, log.header().scenario);
  const Eigen::VectorXd t = log.time();
  nlohmann::json run;
  run["label"] = src.label.empty() ? stem(src.log_path) : src.label;
  run["kind"] = "log";
  run["log"] = shown(options, src.log_path);
  run["scenario"] = log.header().scenario;
  run["t_start"] = t[0];
  run["t_end"] = t[t.size() - 1];
  run["frames"] = runFrames(log, model, rate);
  model.placeWall(settings.wall_x);
  run["static_pose"] = model.staticPoses();
  run["plots"] = logPlots(log, model, plan ? &*plan : nullptr, settings.primitive_start);
  run["metrics"] = logMetrics(log, model, settings.primitive_start);
  run["config_yaml"] = log.header().config_yaml;
  run["ghost"] = nullptr;
  run["plan"] = nullptr;
  if (plan) {
    run["ghost"] = planGhost(*plan, settings.primitive_start, rate, model.boxHalfExtents(model.movingBodies()[0]));
    run["plan"] = planInfo(*plan, shown(options, src.primitive_path));
  }
  return run;
}

nlohmann::json planRun(const RunSource& src, KinematicModel& model, const ReportOptions& options) {
  const double rate = options.pose_rate_hz;
  const std::optional<data::Primitive> plan = loadPlan(src.primitive_path, src.primitive_name, "");
  nlohmann::json run;
  run["label"] = src.label.empty() ? plan->name + " (plan)" : src.label;
  run["kind"] = "plan";
  run["scenario"] = plan->name;
  run["t_start"] = plan->t[0];
  run["t_end"] = plan->t[plan->samples() - 1];
  run["frames"] = nullptr;
  model.placeWall(planWallX(*plan));
  run["static_pose"] = model.staticPoses();
  run["plots"] = planPlots(*plan);
  run["metrics"] = nullptr;
  run["config_yaml"] = plan->config_yaml;
  run["ghost"] = planGhost(*plan, 0.0, rate, model.boxHalfExtents(model.movingBodies()[0]));
  run["plan"] = planInfo(*plan, shown(options, src.primitive_path));
  return run;
}

std::string defaultTitle(const std::vector<RunSource>& runs) {
  if (runs.size() > 1) return "centaur report: " + std::to_string(runs.size()) + " runs";
  const RunSource& r = runs.front();
  return "centaur report: " + (!r.label.empty() ? r.label : stem(r.log_path.empty() ? r.primitive_path : r.log_path));
}

}  // namespace

std::vector<RunSource> runSources(const std::vector<std::string>& logs, const std::string& primitive_path,
                                  const std::string& primitive_name) {
  std::vector<RunSource> out;
  for (const auto& log : logs) out.push_back({"", log, primitive_path, primitive_name});
  if (logs.empty() && !primitive_path.empty()) {
    const std::vector<std::string> names =
        primitive_name.empty() ? data::listPrimitives(primitive_path) : std::vector<std::string>{primitive_name};
    if (names.empty()) throw InputError(primitive_path + ": the file holds no primitive");
    for (const auto& n : names) out.push_back({"", "", primitive_path, n});
  }
  return out;
}

ReportStats writeReport(const std::string& html_path, const std::vector<RunSource>& runs,
                        const ReportOptions& options) {
  if (runs.empty()) throw InputError("report: nothing to show (give a simulation log or --primitive F.h5)");
  if (!(options.pose_rate_hz >= 10.0 && options.pose_rate_hz <= 1000.0)) {
    throw InputError("--rate " + std::to_string(options.pose_rate_hz) + ": must be in [10, 1000] Hz");
  }
  std::vector<std::unique_ptr<data::SimLogFile>> logs;  // every log checked before any work
  for (const RunSource& r : runs) {
    if (r.log_path.empty()) {
      logs.push_back(nullptr);
      continue;
    }
    logs.push_back(std::make_unique<data::SimLogFile>(r.log_path));
    if (logs.back()->header().samples == 0) throw InputError(r.log_path, "t", "the log has no samples");
  }
  std::string model_path = options.model_path;
  for (std::size_t i = 0; i < runs.size() && model_path.empty(); ++i) {
    if (logs[i]) model_path = readLogSettings(*logs[i]).model;
  }
  KinematicModel model(model_path.empty() ? model::centauroMjcfPath() : model_path);
  nlohmann::json list = nlohmann::json::array();
  ReportStats stats;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    list.push_back(logs[i] ? logRun(runs[i], *logs[i], model, options) : planRun(runs[i], model, options));
    if (logs[i]) stats.frames += list.back()["frames"]["frames"].get<std::size_t>();
  }
  const std::string title = options.title.empty() ? defaultTitle(runs) : options.title;
  const nlohmann::json data = {{"format", "centaur-report 1"},
                               {"title", title},
                               {"viewer", std::string(viewerScriptSha256())},
                               {"scene", sceneGeometry(model)},
                               {"runs", std::move(list)}};
  const std::string page = htmlPage(title, data);
  writeTextFileAtomic(html_path, page);
  stats.bytes = page.size();
  stats.runs = runs.size();
  return stats;
}

}  // namespace centaur::report
