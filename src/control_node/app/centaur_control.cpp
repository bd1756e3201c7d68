// centaur-control <task> [--primitive F.h5] [--stabilizer MODE] [--flywheel F.h5] [--start-after S]
//                        [--config F.yaml] [--set key=value]... [--json]
// The controller node (control_node.hpp); `centaur control ...` runs this program. Exit codes as every
// centaur command: 0 done (the robot finished, or SIGINT/SIGTERM), 2 bad input, 4 runtime failure.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <atomic>
#include <cmath>
#include <csignal>
#include <iostream>

#include "common/error.hpp"
#include "control_node/control_node.hpp"

namespace {

std::atomic<bool> g_stop{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler needs a lock-free flag");

extern "C" void onSignal(int) { g_stop.store(true); }

nlohmann::json toJson(const centaur::control_node::ControlNodeReport& r, const std::string& task) {
  nlohmann::json j;
  j["task"] = task;
  j["ticks"] = r.ticks;
  j["commands_sent"] = r.commands_sent;
  j["states_received"] = r.states_received;
  j["states_rejected"] = r.states_rejected;
  j["stale_events"] = r.stale_events;
  j["resets"] = r.resets;
  j["tick_time_us_max"] = r.tick_time_us_max;
  j["robot_finished"] = r.finished;
  return j;
}

}  // namespace

int main(int argc, char** argv) {
  centaur::control_node::ControlNodeArgs a;
  bool json = false;
  CLI::App app{"centaur-control: the online stage (replay, stabilizer, whole-body HQP, force distribution, contact "
               "detection, base estimation) as a DDS node (docs/middleware.md)"};
  app.add_option("task", a.task, "stand | squat-jump | half-squat-jump")->required();
  app.add_option("--primitive", a.primitive_file, "jumps: primitive file (group named like the task)");
  app.add_option("--stabilizer", a.stabilizer, "jumps: upper-body stabilizer")
      ->check(CLI::IsMember({"none", "raibert", "angmom", "ocp"}));
  app.add_option("--flywheel", a.flywheel_file, "jumps, ocp: arm-flywheel plan (centaur plan arm-flywheel)");
  app.add_option("--start-after", a.start_after, "jumps: start the primitive after S seconds of settling "
                                                 "(default: wait for <namespace>/start)")
      ->check(CLI::Range(0.0, 3600.0))
      ->check(CLI::Validator(  // CLI::Range lets NaN through (every comparison with NaN is false)
          [](std::string& text) {
            double v = 0.0;
            return CLI::detail::lexical_cast(text, v) && std::isfinite(v) ? std::string()
                                                                           : "value " + text.substr(0, 40) + " is not a finite number";
          },
          "FINITE"));
  app.add_option("--config", a.config_file, "node configuration (YAML)")->check(CLI::ExistingFile);
  app.add_option("--set", a.overrides, "override a configuration key: --set middleware.domain=3 (repeatable)");
  app.add_flag("--json", json, "print one JSON summary object as the last line of stdout");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : centaur::kExitBadInput;
  }
  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);
  try {
    const auto report = centaur::control_node::runControlNode(a, g_stop);
    std::cout << "control " << a.task << ": " << report.ticks << " ticks, " << report.stale_events
              << " stale events, robot " << (report.finished ? "finished" : "still running") << "\n";
    if (json) std::cout << toJson(report, a.task).dump() << std::endl;
    return centaur::kExitOk;
  } catch (const centaur::InputError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return centaur::kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return centaur::kExitRuntime;
  }
}
