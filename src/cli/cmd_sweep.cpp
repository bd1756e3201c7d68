// centaur sweep SPEC.yaml --out DIR [--jobs N] [--plan-only] [--json]
// A sweep (docs/sweeps.md): the primitive database over a grid of planner parameters (DIR/primitives.h5), every
// grid point simulated with every stabilizer mode under perturbations sampled per run (DIR/results.h5, one row per
// run), the success statistics (DIR/summary.md, DIR/summary.json), heatmaps (DIR/heatmap-<x>-<y>.png) and the
// peak-pitch histograms (DIR/peak-pitch.png). On one
// machine on a pool of threads; under `mpirun -n N` / `srun` across the ranks (rank 0 dispatches and writes).
// Resumes a killed sweep (same SPEC, same DIR); a different spec on an existing DIR is refused.
// Exit codes: 0 the sweep finished (outcomes are data); 2 bad spec or DIR (nothing written); 4 a run failed with
// an error (recorded, the sweep finished) or a runtime failure.
#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>
#include <memory>

#include "cli/command.hpp"
#include "cli/sweep_plots.hpp"
#include "common/error.hpp"
#include "sweep/sweep.hpp"

namespace centaur::cli {
namespace {

struct SweepArgs {
  sweep::SweepOptions options;
  bool json = false;
};

/// The first table of summary.md (success per jump and mode).
std::string modeTable(const std::string& markdown) {
  const auto begin = markdown.find("| jump | mode |");
  if (begin == std::string::npos) return "";
  const auto end = markdown.find("\n\n", begin);
  return markdown.substr(begin, end == std::string::npos ? std::string::npos : end - begin + 1);
}

int runSweepCommand(const SweepArgs& a) {
  sweep::SweepReport r = sweep::runSweep(a.options);
  if (!r.writer) return r.exit_code;  // an MPI worker rank: rank 0 reports
  for (std::size_t i = 0; i < r.summary.heatmaps.size(); ++i) {
    const std::string& dat = r.heatmap_data[i];
    const std::string png = dat.substr(0, dat.size() - 4) + ".png";
    plotHeatmap(r.summary.heatmaps[i], dat, png);
    r.files.push_back(png);
  }
  if (!r.pitch_data.empty()) {
    const std::string png = r.pitch_data.substr(0, r.pitch_data.size() - 4) + ".png";
    plotPitchHistogram(r.summary.pitch, r.pitch_data, png);
    r.files.push_back(png);
  }
  if (a.options.plan_only) {
    std::cout << "sweep: planned the database of " << r.dir << "\n";
  } else {
    std::cout << modeTable(r.summary.markdown) << "\n";
    std::printf("sweep: %zu runs now (%zu finished before, %zu in all) in %.1f s on %d rank%s x %d thread%s: "
                "%.2f runs/s\n",
                r.runs_now, r.runs_before, r.runs_total, r.runs_wall_time_s, r.ranks, r.ranks == 1 ? "" : "s",
                r.threads, r.threads == 1 ? "" : "s", r.runs_wall_time_s > 0 ? r.runs_now / r.runs_wall_time_s : 0.0);
  }
  for (const auto& f : r.files) std::cout << "wrote " << f << "\n";
  if (a.json) {
    nlohmann::json j;
    j["dir"] = r.dir;
    j["runs_total"] = r.runs_total;
    j["runs_before"] = r.runs_before;
    j["runs_now"] = r.runs_now;
    j["ranks"] = r.ranks;
    j["threads"] = r.threads;
    j["wall_time_s"] = r.wall_time_s;
    j["runs_wall_time_s"] = r.runs_wall_time_s;
    j["runs_per_second"] = r.runs_wall_time_s > 0 ? r.runs_now / r.runs_wall_time_s : 0.0;
    j["writer_time_s"] = r.writer_time_s;
    j["summary"] = r.summary.json.is_null() ? nlohmann::json::object() : r.summary.json;
    j["files"] = r.files;
    printJsonLine(j.dump());
  }
  return r.exit_code;
}

const Registrar kSweep{Command{
    "sweep",
    "plan a primitive database over a grid of planner parameters and simulate every point with every stabilizer "
    "under sampled perturbations (threads, or Open MPI under mpirun/srun): results.h5, summary, heatmaps",
    [](CLI::App& sub) -> std::function<int()> {
      auto a = std::make_shared<SweepArgs>();
      sub.add_option("spec", a->options.spec, "sweep specification (YAML; docs/sweeps.md, config/sweeps/)")
          ->required()
          ->check(CLI::ExistingFile);
      sub.add_option("--out", a->options.out, "output directory (a new one, or the same sweep's to resume it)")
          ->required();
      sub.add_option("--jobs", a->options.jobs,
                     "simulation threads per process (0: all cores; under MPI the default is 1 per rank)")
          ->check(CLI::Range(0, 1024))
          ->capture_default_str();
      sub.add_flag("--plan-only", a->options.plan_only, "plan the database (and the arm-flywheel trajectory), then stop");
      sub.add_flag("--json", a->json, "print one JSON object as the last line of stdout");
      return [a]() { return runSweepCommand(*a); };
    }}};

}  // namespace
}  // namespace centaur::cli
