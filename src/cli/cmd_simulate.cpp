// centaur simulate <scenario> [--duration S] [--config F.yaml] [--set key=value]... [--out LOG.h5]
//                             [--video F.mp4] [--snapshot F.png --at T] [--json] [scenario options]
//                             [--select key=value]... (jumps: a grid point of a `centaur sweep` database)
// One sub-command per registered scenario (src/sim/scenario.hpp: built-in `stand`; others register a
// sim::ScenarioRegistrar from their own file and get the common options plus their ScenarioOptions).
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>

#include "cli/command.hpp"
#include "common/error.hpp"
#include "data/primitive_database.hpp"
#include "sim/scenario.hpp"
#include "sim/sim_runner.hpp"

namespace centaur::cli {

namespace {

struct SimulateArgs {
  double duration = -1.0;
  std::string config;
  std::vector<std::string> sets;
  std::string out, video, snapshot;
  double at = -1.0;
  bool json = false;
  std::map<std::string, std::string> options;  // scenario options
  std::vector<std::string> selects;            // --select key=value (a grid point of a sweep database)
  std::string robot;                           // --robot: the key robot.name, after every --set
};

nlohmann::json toJson(const sim::RunSummary& s, const std::string& scenario) {
  nlohmann::json j = sim::summaryJson(s);  // outcome, metrics, counts, the scenario's numbers
  j["scenario"] = scenario;
  j["real_time_factor"] = s.real_time_factor;
  j["wall_time_s"] = s.wall_time_s;
  j["period_time_us_median"] = s.period_time_us_median;
  j["tick_time_us_median"] = s.tick_time_us_median;
  j["tick_time_us_p99"] = s.tick_time_us_p99;
  j["control_period_us"] = s.control_period_us;
  j["ticks_over_period"] = s.ticks_over_period;
  j["tick_over_budget"] = s.tickOverBudget();
  j["video_frames"] = s.video_frames;
  j["files"] = s.files;
  return j;
}

/// `--primitive DB --select key=value...`: the nearest grid point of the database (data/primitive_database.hpp)
/// becomes --primitive-group. A database without --select: its only grid point of the jump, if it has one.
/// Returns the chosen group's description for the JSON line ("" if no database is involved).
nlohmann::json selectFromDatabase(const sim::Scenario& scenario, const std::vector<std::string>& selects,
                                  std::map<std::string, std::string>& options) {
  const auto file = options.find("primitive");
  const bool has_file = file != options.end() && !file->second.empty();
  if (!selects.empty() && !has_file) throw InputError("--select needs --primitive DB.h5 (written by centaur sweep)");
  if (!has_file || options.count("primitive-group") > 0) {
    if (!selects.empty()) throw InputError("--select and --primitive-group exclude each other");
    return nullptr;
  }
  if (selects.empty() && !data::isDatabase(file->second)) return nullptr;
  const data::DatabaseIndex index = data::readDatabaseIndex(file->second);  // InputError if not a database
  std::vector<data::Selection> selections;
  for (const std::string& s : selects) {
    const auto eq = s.find('=');
    if (eq == std::string::npos || eq == 0) throw InputError("--select '" + s + "': expected key=value, e.g. target.height=0.85");
    selections.push_back({s.substr(0, eq), s.substr(eq + 1)});
  }
  if (selections.empty()) {
    std::size_t n = 0;
    for (const auto& e : index.points) n += e.jump == scenario.name && e.solve_status == "solved" ? 1 : 0;
    if (n > 1) {
      std::string axes;
      for (const auto& k : index.axes) axes += (axes.empty() ? "" : ", ") + k;
      throw InputError(file->second + ": a database with " + std::to_string(n) + " grid points of " + scenario.name +
                       "; choose one with --select key=value (axes: " + axes + ")");
    }
  }
  const data::GridEntry& e = index.points[data::selectGridPoint(index, scenario.name, selections, file->second)];
  options["primitive-group"] = e.group;
  nlohmann::json j;
  j["group"] = e.group;
  j["point"] = e.point;
  std::string text;
  for (std::size_t a = 0; a < index.axes.size(); ++a) {
    j["values"][index.axes[a]] = e.values[a].numeric ? nlohmann::json(e.values[a].number) : nlohmann::json(e.values[a].text);
    text += (text.empty() ? "" : ", ") + index.axes[a] + "=" + e.values[a].yaml();
  }
  std::cout << "simulate " << scenario.name << ": grid point " << e.group << " of " << file->second << " ("
            << (text.empty() ? std::string("no axes") : text) << ")\n";
  return j;
}

int runSimulate(const sim::Scenario& scenario, const SimulateArgs& a) {
  std::vector<std::string> overrides = a.sets;
  if (a.duration > 0.0) {
    std::ostringstream os;
    os.precision(17);
    os << "duration=" << a.duration;
    overrides.push_back(os.str());
  }
  if (!a.robot.empty()) overrides.push_back("robot.name=" + a.robot);
  if (!a.snapshot.empty() && a.at < 0.0) throw InputError("--snapshot needs --at T (seconds)");
  sim::RunOutputs outputs;
  outputs.log_path = a.out;
  outputs.video_path = a.video;
  outputs.snapshot_path = a.snapshot;
  outputs.snapshot_time = a.at;
  std::map<std::string, std::string> options = a.options;
  const nlohmann::json selected = selectFromDatabase(scenario, a.selects, options);
  const sim::RunSummary s = sim::runScenario(scenario, a.config, overrides, options, outputs);
  std::cout << "simulate " << scenario.name << ": " << s.outcome << " after " << s.duration_s
            << " s; pelvis drift " << s.pelvis_drift_m * 1000.0 << " mm, peak pitch " << s.peak_pitch_deg
            << " deg, peak roll " << s.peak_roll_deg << " deg, real-time factor " << s.real_time_factor << "\n";
  for (const auto& f : s.files) std::cout << "wrote " << f << "\n";
  if (s.tickOverBudget()) {
    std::fprintf(stderr,
                 "warning: the controller's tick took %.0f us (median; p99 %.0f us, %ld ticks over), more than the "
                 "%.0f us control period: this controller (stack) cannot run at its rate on this machine\n",
                 s.tick_time_us_median, s.tick_time_us_p99, s.ticks_over_period, s.control_period_us);
  }
  if (a.json) {
    nlohmann::json j = toJson(s, scenario.name);
    if (!selected.is_null()) j["grid_point"] = selected;
    printJsonLine(j);
  }
  return kExitOk;  // the run completed; a fall is an outcome (in the summary), not a failure
}

const Registrar registrar{Command{
    "simulate", "simulate CENTAURO in MuJoCo (physics 2 kHz, controller 1 kHz): scenarios stand, ...",
    [](CLI::App& sub) -> std::function<int()> {
      sub.require_subcommand(1);
      auto args = std::make_shared<SimulateArgs>();
      std::vector<std::pair<CLI::App*, const sim::Scenario*>> subs;
      for (const auto& scenario : sim::scenarios()) {
        CLI::App* s = sub.add_subcommand(scenario.name, scenario.help);
        s->add_option("--duration", args->duration, "simulated time [s] (overrides the configuration)")
            ->check(finiteRange(0.001, 3600.0));
        s->add_option("--config", args->config, "scenario configuration (YAML; docs/sim.md)")
            ->check(CLI::ExistingFile);
        s->add_option("--set", args->sets, "override a configuration key: --set world.friction=0.8 (repeatable)");
        s->add_option("--out", args->out, "HDF5 log of the run");
        s->add_option("--video", args->video, "render the run to an mp4 (offscreen, render.fps)");
        s->add_option("--snapshot", args->snapshot, "render one frame to a PNG (with --at)");
        s->add_option("--at", args->at, "snapshot time [s]")->check(finiteRange(0.0, 3600.0));
        s->add_flag("--json", args->json, "print one JSON summary object as the last line of stdout");
        s->add_option("--robot", args->robot,
                      "the robot: a shipped one (models/NAME/) or a robot.yaml (docs/robots.md); default: the key "
                      "robot.name (centauro); the jumps run CENTAURO only so far");
        const bool replays_primitive = std::any_of(scenario.options.begin(), scenario.options.end(),
                                                   [](const sim::ScenarioOption& o) { return o.name == "primitive"; });
        if (replays_primitive) {
          s->add_option("--select", args->selects,
                        "with --primitive DB.h5 of `centaur sweep`: the grid point nearest to key=value (repeatable; "
                        "docs/sweeps.md)");
        }
        for (const auto& o : scenario.options) {
          auto* opt = s->add_option_function<std::string>(
              "--" + o.name, [args, name = o.name](const std::string& v) { args->options[name] = v; }, o.help);
          if (!o.allowed.empty()) opt->check(CLI::IsMember(o.allowed));
          if (o.required) opt->required();
        }
        subs.emplace_back(s, &scenario);
      }
      return [args, subs]() -> int {
        for (const auto& [app, scenario] : subs) {
          if (app->parsed()) return runSimulate(*scenario, *args);
        }
        throw InputError("simulate: choose a scenario");
      };
    }}};

}  // namespace

}  // namespace centaur::cli
