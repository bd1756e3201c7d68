// centaur robot stand|squat-jump|half-squat-jump [--realtime | --lockstep] [--duration S] [--config F.yaml]
//                                                [--set key=value]... [--out LOG.h5] [--json]
// The simulated CENTAURO as a robot on the middleware (robot_node/robot_node.hpp, docs/middleware.md).
#include <nlohmann/json.hpp>

#include <iostream>
#include <memory>
#include <sstream>

#include "cli/command.hpp"
#include "common/error.hpp"
#include "robot_node/robot_node.hpp"

namespace centaur::cli {

namespace {

struct RobotArgs {
  robot_node::RobotNodeArgs node;
  bool realtime = false, lockstep = false, json = false;
  double duration = -1.0;
};

nlohmann::json toJson(const robot_node::RobotNodeResult& r, const std::string& task) {
  const sim::RunSummary& s = r.summary;
  const robot_node::RemoteReport& m = r.remote;
  nlohmann::json j = sim::summaryJson(s);  // the fields of `simulate --json` (outcome, metrics, the task's numbers)
  j["task"] = task;
  j["mode"] = r.lockstep ? "lockstep" : "realtime";
  j["domain"] = r.domain;
  j["real_time_factor"] = s.real_time_factor;
  j["wall_time_s"] = s.wall_time_s;
  j["states_published"] = m.states_published;
  j["commands_received"] = m.guard.received + m.ignored_in_damping;
  j["commands_applied"] = m.guard.applied;
  j["commands_rejected"] = m.guard.rejected;
  j["rejected"] = {{"malformed", m.guard.malformed}, {"non_finite", m.guard.non_finite}, {"gains", m.guard.gains},
                   {"limits", m.guard.limits},       {"stale", m.guard.stale}};
  j["references_clamped"] = m.guard.clamped;
  j["ignored_in_damping"] = m.ignored_in_damping;
  j["late_periods"] = m.late_periods;
  j["watchdog_trips"] = m.watchdog_trips;
  j["resets"] = m.resets;
  j["first_damping_time_s"] =
      m.first_damping_time_s >= 0.0 ? nlohmann::json(m.first_damping_time_s) : nlohmann::json(nullptr);
  j["last_applied_time_s"] = m.last_applied_time_s;
  j["files"] = s.files;
  return j;
}

int runRobot(RobotArgs& a) {
  if (a.realtime && a.lockstep) throw InputError("robot: choose one of --realtime and --lockstep");
  a.node.lockstep = a.lockstep;
  if (a.duration > 0.0) {
    std::ostringstream os;
    os.precision(17);
    os << "duration=" << a.duration;
    a.node.overrides.push_back(os.str());
  }
  const robot_node::RobotNodeResult r = robot_node::runRobotNode(a.node);
  std::cout << "robot " << a.node.task << " (" << (a.lockstep ? "lockstep" : "realtime") << "): " << r.summary.outcome
            << " after " << r.summary.duration_s << " s; commands applied " << r.remote.guard.applied << ", rejected "
            << r.remote.guard.rejected << ", watchdog trips " << r.remote.watchdog_trips << "\n";
  for (const auto& f : r.summary.files) std::cout << "wrote " << f << "\n";
  if (a.json) printJsonLine(toJson(r, a.node.task).dump());
  return kExitOk;
}

const Registrar registrar{Command{
    "robot", "the simulated CENTAURO as a robot on DDS: publishes joint states and IMU, applies checked commands",
    [](CLI::App& sub) -> std::function<int()> {
      auto a = std::make_shared<RobotArgs>();
      sub.add_option("task", a->node.task, "stand | squat-jump | half-squat-jump")
          ->required()
          ->check(CLI::IsMember({"stand", "squat-jump", "half-squat-jump"}));
      sub.add_flag("--realtime", a->realtime, "pace robot time to the wall clock (1x; the default)");
      sub.add_flag("--lockstep", a->lockstep, "advance one period when the command for the last state arrives");
      sub.add_option("--duration", a->duration, "simulated time [s]")->check(finiteRange(0.001, 3600.0));
      sub.add_option("--config", a->node.config_file, "configuration (YAML; docs/sim.md, docs/middleware.md)")
          ->check(CLI::ExistingFile);
      sub.add_option("--set", a->node.overrides, "override a configuration key (repeatable)");
      sub.add_option("--out", a->node.log_path, "HDF5 log of the run (docs/sim.md)");
      sub.add_flag("--json", a->json, "print one JSON summary object as the last line of stdout");
      return [a]() -> int { return runRobot(*a); };
    }}};

}  // namespace

}  // namespace centaur::cli
