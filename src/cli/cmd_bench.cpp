// centaur bench planner [--repeat N] [--set KEY=VALUE]... [--json]
// Cold solves of both jump primitives with the embedded defaults (and the --set overrides, as `centaur plan`'s, for
// both jumps) and both OCP backends (interleaved); reports the
// median wall and CPU solve time, iterations, time per iteration, derivative and factorization time; then warm
// re-plans of two neighbouring problems per jump from the default plan (cli/bench_planner.hpp). With --json the
// last stdout line is one JSON object.
// centaur bench tick [--ticks N] [--stack FILE] [--json]
// The whole-body controller's tick (HQP IK + contact detection + force distribution) timed in closed loop on
// CENTAURO standing in MuJoCo (default stack config/stack_stand.yaml): median / p99 / max of tick() and of its
// HQP update+solve, in microseconds (steady clock).
// centaur bench jump --primitives P.h5 [--flywheel F.h5] [--jumps ...] [--modes ...] [--repeat N] [--json]
// The closed-loop real-time factor of `simulate <jump> --stabilizer <mode>` (physics, impedance and the 1 kHz
// whole-body tick; outputs off), each run alone (one at a time), the (jump, mode) pairs interleaved N times so that
// a change of the machine's speed spreads over all of them; median, min and max per pair.
// centaur bench middleware [--primitives P.h5] [--realtime-priority N] [--json]: the nodes over loopback DDS (cli/bench_middleware.hpp).
// (Timings are measured, never asserted in tests; record them in docs/benchmarks.md.)
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <chrono>
#include <cstdio>

#include "cli/bench_middleware.hpp"
#include "cli/bench_planner.hpp"
#include "cli/command.hpp"
#include "common/error.hpp"
#include "common/stats.hpp"
#include "controller/whole_body_controller.hpp"
#include "stabilizers/stabilizer_stacks.hpp"
#include "sim/compare_runner.hpp"
#include "robot/robot_registry.hpp"
#include "sim/mujoco_robot.hpp"
#include "sim/robot_setup.hpp"
#include "sim/sim_config.hpp"

namespace centaur::cli {
namespace {

struct BenchArgs {
  std::string target;
  int repeat = 3;  // planner: 5 unless given (kBench)
  int ticks = 5000;
  std::string stack;
  bool json = false;
  std::string primitives, flywheel;  // jump: the plans to replay
  int realtime_priority = 0;         // middleware: SCHED_FIFO priority of both nodes (0 = normal scheduling)
  std::vector<std::string> jumps = {"squat-jump", "half-squat-jump"};
  std::vector<std::string> modes = {"none", "raibert", "angmom", "ocp"};
  std::vector<std::string> sets;  // planner: overrides of both jumps' configuration
  std::string robot;              // tick: the robot (models/NAME/ or a robot.yaml); "" = the default
};

// Times every tick() (and the HQP part of it) of the wrapped controller into preallocated buffers.
class TimedController final : public Controller {
 public:
  TimedController(WholeBodyController& c, int ticks) : c_(c) {
    tick_us_.reserve(static_cast<std::size_t>(ticks));
    qp_us_.reserve(static_cast<std::size_t>(ticks));
  }
  void start(const RobotState& s, JointCommand& cmd) override { c_.start(s, cmd); }
  void tick(const RobotState& s, JointCommand& cmd) noexcept override {
    const auto t0 = std::chrono::steady_clock::now();
    c_.tick(s, cmd);
    const auto t1 = std::chrono::steady_clock::now();
    if (tick_us_.size() < tick_us_.capacity()) {
      tick_us_.push_back(1e6 * std::chrono::duration<double>(t1 - t0).count());
      qp_us_.push_back(1e6 * c_.lastQpSeconds());
    }
  }
  std::vector<double> tick_us_, qp_us_;

 private:
  WholeBodyController& c_;
};

nlohmann::json benchTick(const BenchArgs& a) {
  const std::string robot_name = a.robot.empty() ? std::string(robot::kDefaultRobot) : a.robot;
  sim::SimConfig cfg = sim::loadSimConfig("", "", {"robot.name=" + robot_name});
  const sim::SimRobot described = sim::loadSimRobot(robot_name);
  std::string stack = a.stack;
  const bool own_stack = stack.empty() && described.description.name == robot::kDefaultRobot;
  if (own_stack) stack = std::string(CENTAUR_SOURCE_DIR) + "/config/stack_stand.yaml";  // CENTAURO's stand stack
  sim::SimSettings settings = cfg.robot;
  settings.visual_geoms = false;  // as `simulate stand` without --video/--snapshot
  settings.solver = "cg";         // and its contact solver
  sim::MujocoRobot robot(settings);
  WholeBodyParams p;
  p.stack_file = stack;
  // Another robot without --stack: the angular-momentum stabilizer's stack on its frames (same levels as CENTAURO's
  // stand stack: feet / pelvis / momentum + posture).
  if (stack.empty()) p.stack_yaml = angmomStackYaml(cfg.frames);
  p.frames = cfg.frames;
  p.impedance.frames = cfg.frames;
  for (const auto& g : described.description.gains) p.impedance.group_gains[g.group] = {g.kp, g.kd};
  p.dt = robot.controlPeriodSeconds();
  WholeBodyController ctrl(cfg.robot.model_path, p);
  TimedController timed(ctrl, a.ticks);
  RobotState state;
  state.resize(robot.numJoints());
  JointCommand command;
  robot.read(state);
  timed.start(state, command);
  const Eigen::Vector3d p0 = robot.basePosition();
  for (int k = 0; k < a.ticks; ++k) robot.controlPeriod(timed, state, command);
  nlohmann::json j;
  j["target"] = "tick";
  j["ticks"] = a.ticks;
  j["robot"] = described.description.name;
  j["dof"] = ctrl.ikModel().nv();
  j["stack"] = stack.empty() ? std::string("angmom stack on the robot's frames") : stack;
  j["status"] = toString(ctrl.status());
  j["safe_ticks"] = ctrl.counters().safe_ticks;
  j["tick_us_median"] = median(timed.tick_us_);
  j["tick_us_p99"] = percentile(timed.tick_us_, 0.99);
  j["tick_us_max"] = *std::max_element(timed.tick_us_.begin(), timed.tick_us_.end());
  const double period_us = 1e6 * p.dt;
  j["control_period_us"] = period_us;
  j["ticks_over_period"] =
      std::count_if(timed.tick_us_.begin(), timed.tick_us_.end(), [period_us](double x) { return x > period_us; });
  j["over_budget"] = median(timed.tick_us_) > period_us;  // the stack cannot keep the rate on this machine
  j["qp_us_median"] = median(timed.qp_us_);
  j["qp_us_p99"] = percentile(timed.qp_us_, 0.99);
  j["pelvis_drift_m"] = (robot.basePosition() - p0).norm();
  return j;
}

nlohmann::json benchJump(const BenchArgs& a) {
  if (a.primitives.empty()) throw InputError("bench jump: --primitives FILE is required (e.g. out/primitives.h5)");
  const bool ocp = std::find(a.modes.begin(), a.modes.end(), "ocp") != a.modes.end();
  if (ocp && a.flywheel.empty())
    throw InputError("bench jump: mode ocp needs --flywheel FILE (centaur plan arm-flywheel --out FILE)");
  std::vector<sim::BatchRun> runs;
  for (int r = 0; r < a.repeat; ++r) {
    for (const std::string& jump : a.jumps) {
      for (const std::string& mode : a.modes) {
        sim::BatchRun run;
        run.label = jump + "/" + mode;
        run.scenario = jump;
        run.options = {{"primitive", a.primitives}, {"stabilizer", mode}};
        if (mode == "ocp") run.options["flywheel"] = a.flywheel;
        runs.push_back(run);
      }
    }
  }
  sim::BatchCallbacks cb;
  cb.finished = [&](std::size_t i, const sim::BatchResult& res, std::size_t done, std::size_t total) {
    std::fprintf(stderr, "  [%zu/%zu] %-26s %s, real-time factor %.2f\n", done, total, runs[i].label.c_str(),
                 res.status == sim::BatchResult::Status::Completed ? res.summary.outcome.c_str() : res.error.c_str(),
                 res.summary.real_time_factor);
  };
  const std::vector<sim::BatchResult> results = sim::runBatch(runs, 1, cb);
  nlohmann::json j;
  j["target"] = "jump";
  j["repeat"] = a.repeat;
  for (const std::string& jump : a.jumps) {
    for (const std::string& mode : a.modes) {
      std::vector<double> rtf;
      std::string outcome;
      for (std::size_t i = 0; i < runs.size(); ++i) {
        if (runs[i].label != jump + "/" + mode) continue;
        const sim::BatchResult::Status st = results[i].status;
        if (st == sim::BatchResult::Status::BadInput)
          throw InputError("bench jump " + runs[i].label + ": " + results[i].error);
        if (st != sim::BatchResult::Status::Completed)
          throw RuntimeError("bench jump " + runs[i].label + ": " + results[i].error);
        rtf.push_back(results[i].summary.real_time_factor);
        outcome = results[i].summary.outcome;  // deterministic: the same in every repetition
      }
      nlohmann::json& e = j["runs"][jump][mode];
      e["outcome"] = outcome;
      e["real_time_factor_median"] = median(rtf);
      e["real_time_factor_min"] = *std::min_element(rtf.begin(), rtf.end());
      e["real_time_factor_max"] = *std::max_element(rtf.begin(), rtf.end());
    }
  }
  return j;
}

int runBench(const BenchArgs& a) {
  nlohmann::json out;
  if (a.target == "planner") {
    checkPlannerOverrides(a.sets);  // before the first solve
    for (const std::string p : {"squat-jump", "half-squat-jump"}) {
      std::fprintf(stderr, "bench planner %s: %d cold solves ...\n", p.c_str(), a.repeat);
      out["planner"][p] = benchPrimitive(p, a.repeat, a.sets);
      const auto& j = out["planner"][p];
      for (const auto& [b, jb] : j["backends"].items()) {
        std::fprintf(stderr, "  %-16s %-8s %s, %d iterations, median solve %.3f s wall / %.3f s CPU, %.1f ms per iteration",
                     p.c_str(), b.c_str(), jb["status"].get<std::string>().c_str(), jb["iterations"].get<int>(),
                     jb["solve_wall_s_median"].get<double>(), jb["solve_cpu_s_median"].get<double>(),
                     jb["ms_per_iteration"].get<double>());
        std::fprintf(stderr, ", derivatives %.3f s", jb["derivative_wall_s_median"].get<double>());
        if (jb.contains("factorizations_per_iteration")) {
          std::fprintf(stderr, ", %.2f factorizations per iteration (%.3f s), KKT solves %.3f s",
                       jb["factorizations_per_iteration"].get<double>(), jb["factor_wall_s_median"].get<double>(),
                       jb["kkt_solve_wall_s_median"].get<double>());
        }
        std::fprintf(stderr, ", cost %.9g\n", jb["cost"].get<double>());
      }
      std::fprintf(stderr, "  %-16s riccati %.2fx faster than ipopt (median wall)\n", p.c_str(),
                   j["riccati_speedup_wall"].get<double>());
      std::fprintf(stderr, "bench planner %s: warm re-plans of neighbours from the default plan, %d each ...\n",
                   p.c_str(), a.repeat);
      out["planner"][p]["warm_replan"] = benchWarmReplan(p, a.repeat, a.sets);
      const auto& w = out["planner"][p]["warm_replan"];
      for (const auto& [b, jb] : w["backends"].items()) {
        for (const std::string n : w["neighbours"]) {
          std::fprintf(stderr, "  %-16s %-8s %-26s %s, %d iterations (%s start), median solve %.3f s wall, cost %.9g\n",
                       p.c_str(), b.c_str(), n.c_str(), jb[n]["status"].get<std::string>().c_str(),
                       jb[n]["iterations"].get<int>(), jb[n]["start"].get<std::string>().c_str(),
                       jb[n]["solve_wall_s_median"].get<double>(),
                       jb[n]["cost"].get<double>());
        }
      }
    }
  }
  if (a.target == "tick") {
    std::fprintf(stderr, "bench tick: %d ticks of the whole-body controller, CENTAURO standing in MuJoCo ...\n",
                 a.ticks);
    out = benchTick(a);
    std::fprintf(stderr, "  tick median %.1f us, p99 %.1f us, max %.1f us; HQP median %.1f us, p99 %.1f us (%s)\n",
                 out["tick_us_median"].get<double>(), out["tick_us_p99"].get<double>(),
                 out["tick_us_max"].get<double>(), out["qp_us_median"].get<double>(),
                 out["qp_us_p99"].get<double>(), out["status"].get<std::string>().c_str());
    if (out["over_budget"].get<bool>()) {
      std::fprintf(stderr, "  OVER BUDGET: the median tick exceeds the %.0f us control period (%ld of %d ticks over): "
                           "this stack cannot run at 1 kHz on this machine\n",
                   out["control_period_us"].get<double>(), out["ticks_over_period"].get<long>(), a.ticks);
    } else {
      std::fprintf(stderr, "  within the %.0f us control period (%ld of %d ticks over it)\n",
                   out["control_period_us"].get<double>(), out["ticks_over_period"].get<long>(), a.ticks);
    }
  }
  if (a.target == "jump") {
    std::fprintf(stderr, "bench jump: %zu jumps x %zu modes x %d repetitions, one run at a time ...\n",
                 a.jumps.size(), a.modes.size(), a.repeat);
    out = benchJump(a);
    for (const auto& jump : out["runs"].items()) {
      for (const auto& mode : jump.value().items()) {
        const auto& e = mode.value();
        std::fprintf(stderr, "  %-16s %-8s %-8s real-time factor median %.2f [%.2f - %.2f]\n", jump.key().c_str(),
                     mode.key().c_str(), e["outcome"].get<std::string>().c_str(),
                     e["real_time_factor_median"].get<double>(), e["real_time_factor_min"].get<double>(),
                     e["real_time_factor_max"].get<double>());
      }
    }
  }
  if (a.target == "middleware") out = benchMiddleware(a.primitives, a.realtime_priority);
  if (a.json) printJsonLine(out);
  return kExitOk;
}

const Registrar kBench{{"bench",
                        "Measure performance (planner: cold solves of both jumps; tick: whole-body controller; "
                        "jump: closed-loop real-time factor of the simulated jumps; middleware: the nodes over DDS)",
                        [](CLI::App& sub) {
                          auto a = std::make_shared<BenchArgs>();
                          sub.add_option("target", a->target, "what to measure: planner, tick, jump, middleware")
                              ->required()
                              ->check(CLI::IsMember({"planner", "tick", "jump", "middleware"}));
                          sub.add_option("--ticks", a->ticks, "tick: control periods timed (1 ms each)")
                              ->check(CLI::Range(10, 1000000));
                          sub.add_option("--stack", a->stack, "tick: stack YAML (default config/stack_stand.yaml; "
                                                              "another robot: the angmom stack on its frames)");
                          sub.add_option("--robot", a->robot,
                                         "tick: the robot (models/NAME/ or a robot.yaml; default centauro)");
                          CLI::Option* repeat =
                              sub.add_option("--repeat", a->repeat,
                                             "planner: cold runs per case (default 5); jump: runs per (jump, mode) "
                                             "(default 3); median reported")
                                  ->check(CLI::Range(1, 100));
                          sub.add_option("--primitives", a->primitives,
                                         "jump, middleware: primitive file with the jumps")
                              ->check(CLI::ExistingFile);
                          sub.add_option("--realtime-priority", a->realtime_priority,
                                         "middleware: SCHED_FIFO priority of both nodes (middleware.realtime_priority; "
                                         "0 = normal scheduling)")
                              ->check(CLI::Range(0, 98));
                          sub.add_option("--flywheel", a->flywheel, "jump: arm-flywheel file (mode ocp)")
                              ->check(CLI::ExistingFile);
                          sub.add_option("--jumps", a->jumps, "jump: the jumps")
                              ->check(CLI::IsMember({"squat-jump", "half-squat-jump"}));
                          sub.add_option("--modes", a->modes, "jump: the stabilizer modes")
                              ->check(CLI::IsMember({"none", "raibert", "angmom", "ocp"}));
                          sub.add_option("--set", a->sets,
                                         "planner: KEY=VALUE override of both jumps' configuration, as for `plan` "
                                         "(repeatable; e.g. cost.landing_steps=1e-3)");
                          sub.add_flag("--json", a->json, "print a JSON object as the last line of stdout");
                          return [a, repeat]() {
                            // A planner median of 5 solves (the machine's speed varies between runs); a jump run
                            // simulates a whole jump, so 3 there.
                            if (repeat->count() == 0 && a->target == "planner") a->repeat = 5;
                            return runBench(*a);
                          };
                        }}};

}  // namespace
}  // namespace centaur::cli
