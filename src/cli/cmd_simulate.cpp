// centaur simulate <scenario> [--duration S] [--config F.yaml] [--set key=value]... [--out LOG.h5]
//                             [--video F.mp4] [--snapshot F.png --at T] [--json] [scenario options]
// One sub-command per registered scenario (src/sim/scenario.hpp: built-in `stand`; others register a
// sim::ScenarioRegistrar from their own file and get the common options plus their ScenarioOptions).
#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>

#include "cli/command.hpp"
#include "common/error.hpp"
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

int runSimulate(const sim::Scenario& scenario, const SimulateArgs& a) {
  std::vector<std::string> overrides = a.sets;
  if (a.duration > 0.0) {
    std::ostringstream os;
    os.precision(17);
    os << "duration=" << a.duration;
    overrides.push_back(os.str());
  }
  if (!a.snapshot.empty() && a.at < 0.0) throw InputError("--snapshot needs --at T (seconds)");
  sim::RunOutputs outputs;
  outputs.log_path = a.out;
  outputs.video_path = a.video;
  outputs.snapshot_path = a.snapshot;
  outputs.snapshot_time = a.at;
  const sim::RunSummary s = sim::runScenario(scenario, a.config, overrides, a.options, outputs);
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
  if (a.json) printJsonLine(toJson(s, scenario.name));
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
