// centaur plan squat-jump|half-squat-jump|arm-flywheel [--config F.yaml] [--set key=value]... --out F.h5 [--append] [--json]
//   [--warm-start F.h5[:group]] (jumps only: start from a neighbouring primitive's knots)
// Plans a lower-body primitive with the template-model OCP (Ipopt) and writes it to the primitive database;
// arm-flywheel plans the periodic arm trajectory of stabilizer 3 (fixed-base arm OCP, group "arm-flywheel").
// Exit codes: 0 solved; 2 bad input (file, key and allowed range named; no output written);
// 3 not converged (the file IS written, its group attribute solve_status says why); 4 runtime failure.
// The effective configuration is stored in the file (attribute config_yaml) and next to it (<out>.<name>.yaml).
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <utility>

#include "cli/command.hpp"
#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/output_guard.hpp"
#include "common/retain_memory.hpp"
#include "planner/arm_flywheel_problem.hpp"
#include "data/arm_trajectory_io.hpp"
#include "planner/jump_problem.hpp"
#include "data/primitive_io.hpp"
#include "data/primitive_summary.hpp"
#include "model/chain_from_mjcf.hpp"

namespace centaur::cli {
namespace {

// The heap a plan gets on transparent huge pages: the default jumps' solver workspaces need ~20 MiB (a fresh process
// then takes ~1 600 minor page faults in all instead of ~5 600); larger horizons fault the rest in as before.
constexpr std::size_t kPlanHeapBytes = std::size_t{24} << 20;

struct PlanArgs {
  std::string primitive;
  std::string config;
  std::vector<std::string> overrides;
  std::string out;
  bool append = false;
  bool json = false;
  bool quiet = false;
  std::string warm_start;  // F.h5[:group]
  std::string robot;       // --robot: the configuration key `robot`, after every --set
};

/// --warm-start F.h5[:group] as (file, group); the group defaults to the primitive being planned.
std::pair<std::string, std::string> warmStartSource(const PlanArgs& a) {
  std::string file = a.warm_start, group = a.primitive;
  const auto colon = a.warm_start.rfind(':');
  if (colon != std::string::npos && a.warm_start.find('/', colon) == std::string::npos) {  // F.h5:group
    file = a.warm_start.substr(0, colon);
    group = a.warm_start.substr(colon + 1);
  }
  if (file.empty() || group.empty()) throw InputError("--warm-start '" + a.warm_start + "': expected F.h5[:group]");
  return {file, group};
}

// The start of a warm-started plan: the knots of primitive `group` (default: the one being planned) in `file`,
// and its solver multipliers when the file holds them for an OCP of this one's sizes.
planner::WarmStartPoint warmStartPoint(const planner::JumpProblem& problem, const PlanArgs& a) {
  const auto [file, group] = warmStartSource(a);
  const data::Primitive p = data::readPrimitive(file, group);
  planner::WarmStartPoint w = problem.warmStart(p, "--warm-start " + file + ":" + group);
  if (!a.quiet) {
    const char* why = w.hasMultipliers()            ? "its knots and multipliers (primal-dual)"
                      : p.mult_constraints.size() > 0 ? "its knots only (its multipliers belong to an OCP of other sizes)"
                                                      : "its knots only (the file holds no multipliers)";
    std::fprintf(stderr, "  warm start from %s:%s: %s\n", file.c_str(), group.c_str(), why);
  }
  return w;
}

std::string sidecarPath(const std::string& out, const std::string& name) {
  std::filesystem::path p(out);
  return (p.parent_path() / (p.stem().string() + "." + name + ".yaml")).string();
}

// The solver line of the progress output and the solver fields of --json, the same for every primitive.
void printSolveLine(const std::string& name, const planner::SolveResult& result) {
  const data::SolveInfo& info = result.info;
  const planner::SolveStats& st = result.stats;
  std::fprintf(stderr, "%s: %s after %d iterations in %.3f s, cost %.6g, max violation %.2e\n", name.c_str(),
               info.status.c_str(), info.iterations, info.solve_time_s, info.cost, info.max_constraint_violation);
  std::fprintf(stderr, "  backend %s", st.backend.c_str());
  if (!st.first_attempt.status.empty()) {
    std::fprintf(stderr, " (solver.backend auto: riccati ended %s after %d iterations, %.3f s)",
                 st.first_attempt.status.c_str(), st.first_attempt.iterations, st.first_attempt.solve_time_s);
  }
  std::fprintf(stderr, ": derivatives %.3f s", st.derivative_time_s);
  if (st.factorizations >= 0) {
    std::fprintf(stderr, ", %d KKT factorizations (%.2f per iteration) %.3f s, KKT solves %.3f s", st.factorizations,
                 info.iterations > 0 ? static_cast<double>(st.factorizations) / info.iterations : 0.0,
                 st.factor_time_s, st.linear_solve_time_s);
  }
  std::fprintf(stderr, "\n");
}

nlohmann::json solveJson(const std::string& name, const planner::SolveResult& result) {
  const data::SolveInfo& info = result.info;
  nlohmann::json j;
  j["primitive"] = name;
  j["status"] = info.status;
  j["iterations"] = info.iterations;
  j["solve_time_s"] = info.solve_time_s;
  j["cost"] = info.cost;
  j["max_constraint_violation"] = info.max_constraint_violation;
  j["backend"] = result.stats.backend;
  const planner::SolveStats::FirstAttempt& first = result.stats.first_attempt;
  if (!first.status.empty()) {
    j["first_attempt"] = {{"backend", "riccati"},
                          {"status", first.status},
                          {"iterations", first.iterations},
                          {"solve_time_s", first.solve_time_s}};
  }
  return j;
}

// The arm-flywheel trajectory (stabilizer 3): same flags, exit codes and sidecar as the jumps.
int runArmPlan(const PlanArgs& a) {
  const planner::ArmFlywheelConfig cfg = planner::loadArmFlywheelConfig(a.config, a.overrides);
  guardOutputs({{"--config", a.config}, {"model.mjcf", cfg.mjcf.empty() ? model::centauroMjcfPath() : cfg.mjcf}},
               {{"--out", a.out}, {"the effective configuration", sidecarPath(a.out, "arm-flywheel")}});
  if (!a.quiet) std::fprintf(stderr, "planning arm-flywheel (%s) ...\n", cfg.source.c_str());
  const planner::ArmFlywheelProblem problem(cfg);
  const planner::SolveResult result = problem.solve(!a.quiet);
  const data::ArmTrajectory tr = problem.toTrajectory(result);
  data::writeArmTrajectory(a.out, tr, a.append);
  writeTextFileAtomic(sidecarPath(a.out, tr.name), tr.config_yaml);
  const bool ok = result.info.solved();
  const double h_mean = tr.h_ang.col(1).mean(), h_peak = tr.h_ang.col(1).maxCoeff();
  double torque_ratio = 0.0;
  for (int j = 0; j < 7; ++j) torque_ratio = std::max(torque_ratio, tr.tau.col(j).cwiseAbs().maxCoeff() / tr.tau_max_model[j]);
  if (!a.quiet) {
    printSolveLine("arm-flywheel", result);
    std::fprintf(stderr, "  period %.3f s, h_y mean %.3f N m s (peak %.3f), peak |tau|/limit %.2f, written to %s\n",
                 tr.period, h_mean, h_peak, torque_ratio, a.out.c_str());
    if (!ok) std::fprintf(stderr, "warning: the solver did not converge; the file is written and flagged (solve_status)\n");
  }
  if (a.json) {
    nlohmann::json j = solveJson(tr.name, result);
    j["duration_s"] = tr.period;
    j["h_y_mean_Nms"] = h_mean;
    j["h_y_peak_Nms"] = h_peak;
    j["max_torque_ratio"] = torque_ratio;
    j["variables"] = problem.ocp().numVariables();
    j["constraints"] = problem.ocp().numConstraints();
    j["out"] = a.out;
    printJsonLine(j);
  }
  return ok ? kExitOk : kExitNotConverged;
}

int runPlan(const PlanArgs& a) {
  common::shareOneHeap();  // before the planner's threads: a fresh process's first factorization faults less
  common::hugePagesForHeap(kPlanHeapBytes);  // and its workspaces fault in 2 MiB at a time
  if (a.primitive == "arm-flywheel") {
    if (!a.warm_start.empty()) throw InputError("--warm-start: only for squat-jump and half-squat-jump");
    return runArmPlan(a);
  }
  const planner::JumpConfig cfg = planner::loadJumpConfig(a.primitive, a.config, a.overrides);
  // The warm-start file is an input, unless --append updates that same file in place (its primitives are kept).
  const std::string warm_file = a.warm_start.empty() || a.append ? "" : warmStartSource(a).first;
  guardOutputs({{"--config", a.config}, {"--warm-start", warm_file}},
               {{"--out", a.out}, {"the effective configuration", sidecarPath(a.out, a.primitive)}});
  if (!a.quiet) std::fprintf(stderr, "planning %s (%s) ...\n", a.primitive.c_str(), cfg.source.c_str());
  const planner::JumpProblem problem(cfg);
  if (!a.quiet) {
    std::fprintf(stderr, "  %d variables, %d constraints, %d Jacobian and %d Hessian nonzeros\n",
                 problem.ocp().numVariables(), problem.ocp().numConstraints(), problem.ocp().jacobianNonzeros(),
                 problem.ocp().hessianNonzeros());
  }
  const planner::SolveResult result =
      a.warm_start.empty() ? problem.solve(!a.quiet) : problem.solve(!a.quiet, warmStartPoint(problem, a));
  const data::Primitive prim = problem.toPrimitive(result);
  data::writePrimitives(a.out, {prim}, a.append ? data::WriteMode::Append : data::WriteMode::Replace);
  writeTextFileAtomic(sidecarPath(a.out, prim.name), prim.config_yaml);
  const auto s = data::summarize(prim);
  const bool ok = result.info.solved();
  if (!a.quiet) {
    printSolveLine(prim.name, result);
    std::fprintf(stderr, "  duration %.3f s, flight %.3f s, apex waist height %.3f m (+%.3f m), written to %s\n",
                 s.duration, s.flight_time, s.apex_height, s.apex_gain, a.out.c_str());
    if (!ok) std::fprintf(stderr, "warning: the solver did not converge; the file is written and flagged (solve_status)\n");
  }
  if (a.json) {
    nlohmann::json j = solveJson(prim.name, result);
    j["duration_s"] = s.duration;
    j["flight_time_s"] = s.flight_time;
    j["apex_height_m"] = s.apex_height;
    j["apex_gain_m"] = s.apex_gain;
    j["variables"] = problem.ocp().numVariables();
    j["constraints"] = problem.ocp().numConstraints();
    j["out"] = a.out;
    printJsonLine(j);
  }
  return ok ? kExitOk : kExitNotConverged;
}

const Registrar kPlan{{"plan", "Plan a lower-body primitive (template-model OCP solved with Ipopt)", [](CLI::App& sub) {
                         auto a = std::make_shared<PlanArgs>();
                         sub.add_option("primitive", a->primitive, "squat-jump | half-squat-jump | arm-flywheel")
                             ->required()
                             ->check(CLI::IsMember({"squat-jump", "half-squat-jump", "arm-flywheel"}));
                         sub.add_option("--config", a->config, "YAML configuration (overrides the embedded defaults)");
                         sub.add_option("--set", a->overrides, "override one key, e.g. --set target.height=1.05")
                             ->take_all();
                         sub.add_option("--out", a->out, "output primitive file (HDF5)")->required();
                         sub.add_flag("--append", a->append, "add to (or replace in) an existing file");
                         sub.add_flag("--json", a->json, "print a JSON summary as the last line of stdout");
                         sub.add_flag("--quiet", a->quiet, "no progress on stderr");
                         sub.add_option("--warm-start", a->warm_start,
                                        "start from the knots of a neighbouring primitive F.h5[:group] (same horizon; "
                                        "group defaults to the primitive planned)");
                         sub.add_option("--robot", a->robot,
                                        "the robot: a shipped one (models/NAME/) or a robot.yaml (docs/robots.md); "
                                        "default: the configuration's key robot (centauro)");
                         return [a]() {
                           if (!a->robot.empty()) {
                             if (a->primitive == "arm-flywheel") {
                               throw InputError("plan arm-flywheel: --robot is not available yet (it plans the arm of "
                                                "the MJCF of key mjcf)");
                             }
                             a->overrides.push_back("robot=" + a->robot);
                           }
                           return runPlan(*a);
                         };
                       }}};

}  // namespace
}  // namespace centaur::cli
