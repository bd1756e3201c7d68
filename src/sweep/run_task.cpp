#include "sweep/run_task.hpp"

#include <cctype>
#include <chrono>
#include <cmath>
#include <exception>

#include "common/error.hpp"
#include "sim/scenario.hpp"
#include "sim/sim_runner.hpp"
#include "sweep/run_plan.hpp"

namespace centaur::sweep {

namespace {

std::map<std::string, std::string> scenarioOptions(const RunContext& ctx, const RunId& id) {
  const std::string& mode = ctx.spec->modes[id.mode];
  std::map<std::string, std::string> options = {{"primitive", ctx.primitives},
                                                {"primitive-group", ctx.index.points.at(id.point).group},
                                                {"stabilizer", mode}};
  if (mode == "ocp") options["flywheel"] = ctx.flywheel;
  return options;
}

void fill(RunRecord& r, const sim::RunSummary& s) {
  auto set = [&](const char* name, double value) { r.set(name, value); };
  r.outcome = s.outcome;
  set("peak_pitch_deg", s.peak_pitch_deg);
  set("max_torque_ratio", s.max_torque_ratio);
  set("fall_time_s", s.fall_time_s >= 0.0 ? s.fall_time_s : std::nan(""));
  set("duration_s", s.duration_s);
  set("real_time_factor", s.real_time_factor);
  for (const char* name : {"pitch_rms_deg", "peak_imu_pitch_deg", "wall_contact_s", "flight_time_s", "apex_height_m",
                           "final_pitch_deg", "final_height_error_m"}) {
    const auto it = s.extra.find(name);
    if (it != s.extra.end()) set(name, it->second);
  }
}

/// `s` quoted for a POSIX shell when it holds anything but [A-Za-z0-9_./=+,:@-].
std::string shellQuote(const std::string& s) {
  bool plain = !s.empty();
  for (char c : s) {
    plain = plain && (std::isalnum(static_cast<unsigned char>(c)) || std::string("_./=+,:@-").find(c) != std::string::npos);
  }
  if (plain) return s;
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace

RunRecord executeRun(const RunContext& ctx, std::size_t run) {
  const RunId id = runId(*ctx.spec, run);
  RunRecord r;
  r.run = static_cast<std::int64_t>(run);
  const data::GridEntry& point = ctx.index.points.at(id.point);
  if (point.solve_status != "solved") {
    r.outcome = kOutcomeNotPlanned;
    r.error = "the plan of " + point.group + " did not converge (" + point.solve_status + ")";
    return r;
  }
  const auto t0 = std::chrono::steady_clock::now();
  try {
    const sim::Scenario* scenario = sim::findScenario(point.jump);
    if (scenario == nullptr) throw RuntimeError("no scenario '" + point.jump + "'");
    const sim::RunSummary s = sim::runScenario(*scenario, "", runOverrides(*ctx.spec, id.point, id.seed_index),
                                               scenarioOptions(ctx, id), sim::RunOutputs{});
    fill(r, s);
  } catch (const std::exception& e) {
    r = RunRecord();
    r.run = static_cast<std::int64_t>(run);
    r.outcome = kOutcomeError;
    r.error = e.what();
  }
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.set("run_time_s", elapsed);
  return r;
}

std::string replayCommand(const RunContext& ctx, std::size_t run) {
  const SweepSpec& spec = *ctx.spec;
  const RunId id = runId(spec, run);
  const data::GridEntry& point = ctx.index.points.at(id.point);
  const std::string& mode = spec.modes[id.mode];
  std::string cmd = "centaur simulate " + point.jump + " --primitive " + shellQuote(ctx.primitives);
  if (spec.axes.empty()) {
    cmd += " --primitive-group " + shellQuote(point.group);
  } else {
    for (std::size_t a = 0; a < spec.axes.size(); ++a) {
      cmd += " --select " + shellQuote(spec.axes[a].key + "=" + point.values[a].yaml());
    }
  }
  cmd += " --stabilizer " + mode;
  if (mode == "ocp") cmd += " --flywheel " + shellQuote(ctx.flywheel);
  for (const std::string& o : runOverrides(spec, id.point, id.seed_index)) cmd += " --set " + shellQuote(o);
  return cmd;
}

}  // namespace centaur::sweep
