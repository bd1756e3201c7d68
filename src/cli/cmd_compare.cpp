// centaur compare [--out DIR] [--json] [--jobs N] [--jumps squat-jump,half-squat-jump]
//                 [--modes none,raibert,angmom,ocp] [--set key=value]... [--primitives F.h5] [--flywheel F.h5]
// The paper's Fig. 4: plans the jumps once (DIR/primitives.h5, unless --primitives is given) and, with mode ocp
// when the jump scenarios take a `flywheel` option, the arm-flywheel trajectory (DIR/arm-flywheel.h5, unless
// --flywheel is given); simulates every (jump, stabilizer mode) pair in-process on a thread pool
// (DIR/<jump>-<mode>.h5, each with its effective configuration DIR/<jump>-<mode>.config.yaml); writes
// DIR/compare.md, DIR/compare.json, DIR/compare-pitch.csv, DIR/compare-pitch.png (IMU pitch over time, one
// panel per jump) and DIR/report.html (every run replayed in 3D with a run selector, docs/report.md).
// Exit codes: 0 every run completed (a fall is an outcome, not an error); 2 bad input (nothing written when
// detected before the runs); 4 runtime failure (a run, planning or plotting failed; what completed is written).
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <set>

#include "cli/command.hpp"
#include "cli/compare_plot.hpp"
#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/output_guard.hpp"
#include "planner/arm_flywheel_problem.hpp"
#include "data/arm_trajectory_io.hpp"
#include "planner/jump_problem.hpp"
#include "data/primitive_io.hpp"
#include "report/report.hpp"
#include "sim/compare_pitch.hpp"
#include "sim/compare_report.hpp"
#include "sim/compare_runner.hpp"
#include "sim/scenario.hpp"
#include "sim/sim_config.hpp"

namespace centaur::cli {
namespace {

namespace fs = std::filesystem;

struct CompareArgs {
  std::string out = "out/compare";
  bool json = false;
  int jobs = 0;
  std::vector<std::string> jumps{"squat-jump", "half-squat-jump"};
  std::vector<std::string> modes{"none", "raibert", "angmom", "ocp"};
  std::vector<std::string> sets;
  std::string primitives;  // existing primitive file; "" = plan into DIR/primitives.h5
  std::string flywheel;    // existing arm-flywheel file; "" = plan into DIR/arm-flywheel.h5 (when needed)
};

std::string join(const std::vector<std::string>& v, const char* sep = ", ") {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : sep) + x;
  return s;
}

const sim::ScenarioOption* findOption(const sim::Scenario& s, const std::string& name) {
  for (const auto& o : s.options) {
    if (o.name == name) return &o;
  }
  return nullptr;
}

/// Everything that can be checked before anything is written; throws InputError.
std::vector<const sim::Scenario*> validate(const CompareArgs& a) {
  if (a.jumps.empty()) throw InputError("--jumps: give at least one jump (squat-jump, half-squat-jump)");
  if (a.modes.empty()) throw InputError("--modes: give at least one mode (none, raibert, angmom, ocp)");
  if (std::set<std::string>(a.jumps.begin(), a.jumps.end()).size() != a.jumps.size()) {
    throw InputError("--jumps '" + join(a.jumps, ",") + "': a jump is listed twice");
  }
  if (std::set<std::string>(a.modes.begin(), a.modes.end()).size() != a.modes.size()) {
    throw InputError("--modes '" + join(a.modes, ",") + "': a mode is listed twice");
  }
  std::error_code ec;
  if (fs::exists(a.out, ec) && !fs::is_directory(a.out, ec)) {
    throw InputError("--out " + a.out + ": exists and is not a directory");
  }
  std::vector<const sim::Scenario*> scenarios;
  for (const auto& jump : a.jumps) {
    const sim::Scenario* s = sim::findScenario(jump);
    if (s == nullptr || findOption(*s, "primitive") == nullptr || findOption(*s, "stabilizer") == nullptr) {
      throw InputError("--jumps: '" + jump + "' is not a jump scenario (allowed: squat-jump, half-squat-jump)");
    }
    const sim::ScenarioOption* stab = findOption(*s, "stabilizer");
    for (const auto& m : a.modes) {
      if (!stab->allowed.empty() && std::find(stab->allowed.begin(), stab->allowed.end(), m) == stab->allowed.end()) {
        throw InputError("--modes: '" + m + "' is not a stabilizer of " + jump + " (allowed: " + join(stab->allowed) +
                         ")");
      }
    }
    sim::loadSimConfig(s->defaults_yaml, "", a.sets);  // bad --set keys/values: InputError naming them
    if (a.primitives.empty()) {
      planner::loadJumpConfig(jump, "", {});  // the jump can be planned
    } else {
      data::readPrimitive(a.primitives, jump);  // InputError naming the file and the available names
    }
    scenarios.push_back(s);
  }
  if (!a.flywheel.empty()) data::readArmTrajectory(a.flywheel);  // InputError naming the file and dataset
  return scenarios;
}

/// True if the OCP stabilizer runs and the jump scenarios take its trajectory as the `flywheel` option.
bool needsFlywheel(const CompareArgs& a, const std::vector<const sim::Scenario*>& scenarios) {
  if (std::find(a.modes.begin(), a.modes.end(), "ocp") == a.modes.end()) return false;
  for (const auto* s : scenarios) {
    if (findOption(*s, "flywheel") != nullptr) return true;
  }
  return false;
}

/// Plan the arm-flywheel trajectory with its defaults into `path` (plus <stem>.arm-flywheel.yaml); its status.
std::string planFlywheel(const std::string& path, std::vector<std::string>& files) {
  const auto t0 = std::chrono::steady_clock::now();
  const planner::ArmFlywheelProblem problem(planner::loadArmFlywheelConfig("", {}));
  const planner::SolveResult result = problem.solve(false);
  const data::ArmTrajectory tr = problem.toTrajectory(result);
  const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::fprintf(stderr, "compare: planned arm-flywheel: %s, %d iterations, %.1f s\n", result.info.status.c_str(),
               result.info.iterations, dt);
  if (!result.info.solved()) {
    std::fprintf(stderr, "compare: warning: arm-flywheel did not converge; its trajectory is used as it is\n");
  }
  data::writeArmTrajectory(path, tr, false);
  files.push_back(path);
  const fs::path f(path);
  const std::string sidecar = (f.parent_path() / (f.stem().string() + "." + tr.name + ".yaml")).string();
  writeTextFileAtomic(sidecar, tr.config_yaml);
  files.push_back(sidecar);
  return result.info.status;
}

/// Plan every jump with its defaults into `path` (plus <stem>.<jump>.yaml); returns (name, status) pairs.
std::vector<std::pair<std::string, std::string>> planJumps(const std::vector<std::string>& jumps,
                                                           const std::string& path, std::vector<std::string>& files) {
  std::vector<data::Primitive> prims;
  std::vector<std::pair<std::string, std::string>> status;
  for (const auto& jump : jumps) {
    const auto t0 = std::chrono::steady_clock::now();
    const planner::JumpConfig cfg = planner::loadJumpConfig(jump, "", {});
    const planner::JumpProblem problem(cfg);
    const planner::SolveResult result = problem.solve(false);
    prims.push_back(problem.toPrimitive(result));
    const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::fprintf(stderr, "compare: planned %s: %s, %d iterations, %.1f s\n", jump.c_str(),
                 result.info.status.c_str(), result.info.iterations, dt);
    if (!result.info.solved()) {
      std::fprintf(stderr, "compare: warning: %s did not converge; its primitive is used as it is (flagged)\n",
                   jump.c_str());
    }
    status.emplace_back(jump, result.info.status);
  }
  data::writePrimitives(path, prims, data::WriteMode::Replace);
  files.push_back(path);
  for (const auto& p : prims) {
    const fs::path f(path);
    const std::string sidecar = (f.parent_path() / (f.stem().string() + "." + p.name + ".yaml")).string();
    writeTextFileAtomic(sidecar, p.config_yaml);
    files.push_back(sidecar);
  }
  return status;
}

/// DIR/report.html (written to `path`, in the staging directory): every completed run replayed in 3D with its
/// plan as a ghost, a run selector (docs/report.md). `shown`: the staged inputs under their final names.
void writeCompareReport(const std::string& path, const std::vector<report::RunSource>& runs,
                        const std::map<std::string, std::string>& shown) {
  report::ReportOptions options;
  options.title = "centaur compare: " + std::to_string(runs.size()) + " run" + (runs.size() == 1 ? "" : "s");
  options.shown_paths = shown;
  try {
    report::writeReport(path, runs, options);
  } catch (const InputError& e) {  // our own logs and plans: a runtime failure, not the user's input
    throw RuntimeError(e.what());
  }
}

std::string fmt(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

/// Every file compare will write into DIR, for guardOutputs().
std::vector<NamedPath> compareOutputs(const CompareArgs& a, bool flywheel) {
  std::vector<std::string> names{"compare.md", "compare.json", "compare-pitch.csv", "compare-pitch.png", "report.html"};
  if (a.primitives.empty()) {
    names.push_back("primitives.h5");
    for (const auto& jump : a.jumps) names.push_back("primitives." + jump + ".yaml");
  }
  if (flywheel) names.insert(names.end(), {"arm-flywheel.h5", "arm-flywheel.arm-flywheel.yaml"});
  for (const auto& jump : a.jumps) {
    for (const auto& mode : a.modes) names.insert(names.end(), {jump + "-" + mode + ".h5", jump + "-" + mode + ".config.yaml"});
  }
  std::vector<NamedPath> out;
  for (const auto& n : names) out.push_back({"--out " + a.out + ":", (fs::path(a.out) / n).string()});
  return out;
}

// One (jump, stabilizer) run of compare and its log.
struct ComparePair {
  std::string jump, mode, log;
};

// What the completed runs give the table, the pitch plot and the report.
struct CompareOutcome {
  std::vector<sim::CompareRow> rows;
  std::vector<std::string> names;  // labels of the completed runs, in order
  std::vector<sim::PitchSeries> series;
  std::vector<report::RunSource> report_runs;
  std::vector<PitchPanel> panels;
  bool failed = false;
};

// A staged output's path as it will be once committed ("" stays "").
std::string finalName(const StagedOutputs& staged, const std::string& path) {
  return path.empty() ? path : staged.finalPath(fs::path(path).filename().string());
}

// Every (jump, stabilizer) pair as a batch run logging into the staging directory.
std::vector<sim::BatchRun> compareRuns(const CompareArgs& a, const std::vector<const sim::Scenario*>& scenarios,
                                       const std::string& primitives, const std::string& flywheel,
                                       const StagedOutputs& staged, std::vector<ComparePair>& pairs) {
  std::vector<sim::BatchRun> runs;
  for (std::size_t j = 0; j < a.jumps.size(); ++j) {
    for (const auto& mode : a.modes) {
      ComparePair p{a.jumps[j], mode, staged.path(a.jumps[j] + "-" + mode + ".h5")};
      sim::BatchRun r;
      r.label = p.jump + "/" + mode;
      r.scenario = p.jump;
      r.options = {{"primitive", primitives}, {"stabilizer", mode}};
      const bool takes_flywheel = findOption(*scenarios[j], "flywheel") != nullptr;
      if (takes_flywheel && !flywheel.empty()) r.options["flywheel"] = flywheel;
      r.overrides = a.sets;
      r.outputs.log_path = p.log;
      // Without a trajectory file the OCP stabilizer may solve its arm OCP (Ipopt + MUMPS, not thread-safe)
      // while it is set up: such runs go one at a time.
      if (mode == "ocp" && !r.options.count("flywheel")) r.exclusive_group = "ipopt";
      runs.push_back(std::move(r));
      pairs.push_back(std::move(p));
    }
  }
  return runs;
}

// The runs on `threads` threads, each reported on stderr as it starts and ends.
std::vector<sim::BatchResult> runCompareBatch(const std::vector<sim::BatchRun>& runs, int jobs, int threads,
                                              double& wall_s) {
  std::fprintf(stderr, "compare: %zu runs on %d thread%s\n", runs.size(), threads, threads == 1 ? "" : "s");
  sim::BatchCallbacks cb;
  cb.started = [&](std::size_t i) { std::fprintf(stderr, "compare: started %s\n", runs[i].label.c_str()); };
  cb.finished = [&](std::size_t i, const sim::BatchResult& r, std::size_t done, std::size_t total) {
    if (r.status == sim::BatchResult::Status::Completed) {
      std::fprintf(stderr, "compare: [%zu/%zu] %s: %s, peak pitch %.2f deg, %.1f s simulated in %.1f s (x%.2f)\n",
                   done, total, runs[i].label.c_str(), r.summary.outcome.c_str(), r.summary.peak_pitch_deg,
                   r.summary.duration_s, r.elapsed_s, r.summary.real_time_factor);
    } else {
      std::fprintf(stderr, "compare: [%zu/%zu] %s FAILED: %s\n", done, total, runs[i].label.c_str(), r.error.c_str());
    }
  };
  const auto t_runs = std::chrono::steady_clock::now();
  std::vector<sim::BatchResult> results = sim::runBatch(runs, jobs, cb);
  wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_runs).count();
  std::fprintf(stderr, "compare: %zu runs in %.1f s wall time\n", runs.size(), wall_s);
  return results;
}

// The table's rows, the pitch histories and the report's runs of the completed runs (their logs and configs go
// into `files`); InputError, with nothing written, if a run had bad input.
CompareOutcome collectCompare(const CompareArgs& a, const std::vector<ComparePair>& pairs,
                              const std::vector<sim::BatchRun>& runs, const std::vector<sim::BatchResult>& results,
                              const std::string& primitives, const StagedOutputs& staged,
                              std::vector<std::string>& files) {
  CompareOutcome o;
  bool bad_input = false;
  for (const auto& jump : a.jumps) o.panels.push_back({jump, {}});
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const sim::BatchResult& r = results[i];
    const bool ok = r.status == sim::BatchResult::Status::Completed;
    bad_input = bad_input || r.status == sim::BatchResult::Status::BadInput;
    o.failed = o.failed || !ok;
    o.rows.push_back(sim::makeCompareRow(pairs[i].jump, pairs[i].mode, r, ok ? finalName(staged, pairs[i].log) : ""));
    if (!ok) continue;
    files.insert(files.end(), r.summary.files.begin(), r.summary.files.end());
    for (const auto& f : r.summary.files) files.push_back(sim::configPathFor(f));
    try {
      o.series.push_back(sim::readLogPitch(pairs[i].log));
    } catch (const InputError& e) {  // our own log unreadable: a runtime failure, not the user's input
      throw RuntimeError(e.what());
    }
    o.names.push_back(runs[i].label);
    o.report_runs.push_back({pairs[i].jump + " / " + pairs[i].mode + " (" + r.summary.outcome + ")", pairs[i].log,
                             primitives, pairs[i].jump});
    const std::size_t panel = static_cast<std::size_t>(
        std::find(a.jumps.begin(), a.jumps.end(), pairs[i].jump) - a.jumps.begin());
    if (!o.series.back().t.empty()) {
      PitchPanel& pp = o.panels[panel];
      const double t0 = o.series.back().t.front(), t1 = o.series.back().t.back();
      pp.t_min = pp.curves.empty() ? t0 : std::min(pp.t_min, t0);
      pp.t_max = pp.curves.empty() ? t1 : std::max(pp.t_max, t1);
    }
    o.panels[panel].curves.push_back({static_cast<int>(o.names.size()) + 1,
                                      pairs[i].mode + " (" + r.summary.outcome + ")", modeColour(pairs[i].mode)});
  }
  if (bad_input) {  // nothing is written: the staging directory goes with its contents
    for (std::size_t i = 0; i < runs.size(); ++i) {
      if (results[i].status != sim::BatchResult::Status::BadInput) continue;
      throw InputError(results[i].error + " (in run " + runs[i].label + "; nothing was written)");
    }
  }
  return o;
}

// compare.md, compare.json and, with any pitch history, compare-pitch.csv/.png and report.html, staged; returns
// the table.
std::string writeCompareFiles(const CompareArgs& a, const CompareOutcome& o, const nlohmann::json& runs_json,
                              const StagedOutputs& staged, std::vector<std::string>& files) {
  const std::string md_path = staged.path("compare.md");
  const std::string json_path = staged.path("compare.json");
  const std::string csv_path = staged.path("compare-pitch.csv");
  const std::string png_path = staged.path("compare-pitch.png");
  const std::string table = sim::compareMarkdown(o.rows);
  writeTextFileAtomic(md_path, "# centaur compare: jumps x upper-body stabilizers\n\n" + table +
                                   "\nPeak pitch: pelvis, ground truth. Pitch RMS: IMU pitch (ZYX pitch of "
                                   "w_R_imu). Max torque ratio: peak |tau| / effort limit. Real-time factor: "
                                   "simulated time / wall time of the loop.\n"
                                   "Plot: compare-pitch.png (data: compare-pitch.csv). Logs: <jump>-<mode>.h5.\n");
  writeTextFileAtomic(json_path, runs_json.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
  files.push_back(md_path);
  files.push_back(json_path);
  if (!o.series.empty()) {
    writeTextFileAtomic(csv_path, sim::pitchCsv(o.names, o.series));
    files.push_back(csv_path);
    plotPitchPanels(csv_path, o.panels, png_path);
    files.push_back(png_path);
    std::map<std::string, std::string> shown;
    for (const report::RunSource& r : o.report_runs) {
      for (const std::string& p : {r.log_path, r.primitive_path}) shown[p] = finalName(staged, p);
    }
    if (!a.primitives.empty()) shown.erase(a.primitives);  // the user's file, not staged
    const std::string report_path = staged.path("report.html");
    writeCompareReport(report_path, o.report_runs, shown);
    files.push_back(report_path);
  }
  return table;
}

int runCompare(const CompareArgs& a) {
  const auto t_start = std::chrono::steady_clock::now();
  const std::vector<const sim::Scenario*> scenarios = validate(a);
  const bool plan_flywheel = a.flywheel.empty() && needsFlywheel(a, scenarios);
  guardOutputs({{"--primitives", a.primitives}, {"--flywheel", a.flywheel}}, compareOutputs(a, plan_flywheel));
  // Everything is written into a staging directory inside DIR and moved into DIR at the end: a run that fails on
  // bad input, an error or a signal leaves nothing behind.
  StagedOutputs staged(a.out);
  std::vector<std::string> files;  // staged paths; reported under their final names

  // 1. primitives
  std::string primitives = a.primitives;
  nlohmann::json plan_json = nlohmann::json::array();
  if (primitives.empty()) {
    primitives = staged.path("primitives.h5");
    for (const auto& [name, status] : planJumps(a.jumps, primitives, files)) {
      plan_json.push_back({{"primitive", name}, {"status", status}});
    }
  }
  std::string flywheel = a.flywheel;
  if (plan_flywheel) {
    flywheel = staged.path("arm-flywheel.h5");
    plan_json.push_back({{"primitive", "arm-flywheel"}, {"status", planFlywheel(flywheel, files)}});
  }

  // 2. the runs; 3. table, pitch histories, plot, report
  std::vector<ComparePair> pairs;
  const std::vector<sim::BatchRun> runs = compareRuns(a, scenarios, primitives, flywheel, staged, pairs);
  const int threads = sim::batchThreads(a.jobs, runs.size());
  double runs_wall = 0.0;
  const std::vector<sim::BatchResult> results = runCompareBatch(runs, a.jobs, threads, runs_wall);
  const CompareOutcome outcome = collectCompare(a, pairs, runs, results, primitives, staged, files);
  const nlohmann::json runs_json = sim::compareJson(outcome.rows);
  const std::string table = writeCompareFiles(a, outcome, runs_json, staged, files);
  staged.commit();
  for (auto& f : files) f = finalName(staged, f);
  const double total_wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();

  // 4. report
  std::cout << table << "\n";
  std::cout << "compare: " << runs.size() << " runs in " << fmt("%.1f", runs_wall) << " s wall time on " << threads
            << " thread" << (threads == 1 ? "" : "s") << " (total " << fmt("%.1f", total_wall) << " s)\n";
  for (const auto& f : files) std::cout << "wrote " << f << "\n";
  if (a.json) {
    nlohmann::json j;
    j["runs"] = runs_json;
    j["files"] = files;
    j["wall_time_s"] = total_wall;
    j["runs_wall_time_s"] = runs_wall;
    j["threads"] = threads;
    j["primitives"] = a.primitives.empty() ? finalName(staged, primitives) : primitives;
    j["flywheel"] = flywheel.empty() ? nlohmann::json(nullptr)
                                     : nlohmann::json(a.flywheel.empty() ? finalName(staged, flywheel) : flywheel);
    j["planned"] = plan_json;
    printJsonLine(j);
  }
  return outcome.failed ? kExitRuntime : kExitOk;
}

const Registrar kCompare{Command{
    "compare",
    "simulate every jump with every upper-body stabilizer and compare them (table, JSON, IMU pitch plot: Fig. 4)",
    [](CLI::App& sub) -> std::function<int()> {
      auto a = std::make_shared<CompareArgs>();
      sub.add_option("--out", a->out, "output directory")->capture_default_str();
      sub.add_flag("--json", a->json, "print one JSON object as the last line of stdout");
      sub.add_option("--jobs", a->jobs, "runs at the same time (0 = hardware concurrency)")
          ->check(CLI::Range(0, 256))
          ->capture_default_str();
      sub.add_option("--jumps", a->jumps, "comma-separated jumps")->delimiter(',')->capture_default_str();
      sub.add_option("--modes", a->modes, "comma-separated stabilizer modes")->delimiter(',')->capture_default_str();
      sub.add_option("--set", a->sets, "override a simulation configuration key in every run (repeatable)");
      sub.add_option("--primitives", a->primitives, "use the primitives of this file instead of planning them")
          ->check(CLI::ExistingFile);
      sub.add_option("--flywheel", a->flywheel,
                     "ocp mode: use the arm-flywheel trajectory of this file instead of planning it")
          ->check(CLI::ExistingFile);
      return [a]() { return runCompare(*a); };
    }}};

}  // namespace
}  // namespace centaur::cli
