// Standing closed loop on CENTAURO: one iteration = one 1 ms control period = 2 physics steps at 2 kHz
// with the joint impedance law + one controller tick. Counter `rtf` = simulated time / CPU time
// (real-time factor on one core). Run:
//   ./build/bench/bench_sim_stand --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include "controller/standing_controller.hpp"
#include "sim/mujoco_robot.hpp"
#include "sim/sim_config.hpp"

using namespace centaur;

namespace {

/// Constant command (the home posture, no feed-forward): physics + impedance only.
class ConstantController : public Controller {
 public:
  explicit ConstantController(const Eigen::VectorXd& q) : q_(q) {}
  void start(const RobotState& s, JointCommand& c) override {
    c.resize(s.q.size());
    c.q_ref = q_;
    c.kp.setConstant(500.0);
    c.kd.setConstant(5.0);
  }
  void tick(const RobotState&, JointCommand&) noexcept override {}

 private:
  Eigen::VectorXd q_;
};

void runLoop(benchmark::State& st, sim::MujocoRobot& robot, Controller& ctrl) {
  RobotState state;
  state.resize(robot.numJoints());
  JointCommand command;
  robot.read(state);
  ctrl.start(state, command);
  robot.write(command);
  long periods = 0;
  for (auto _ : st) {
    robot.controlPeriod(ctrl, state, command);
    if (++periods % 20000 == 0) {  // keep standing near the start: reset every 20 s of simulated time
      st.PauseTiming();
      robot.reset();
      robot.read(state);
      ctrl.start(state, command);
      robot.write(command);
      st.ResumeTiming();
    }
  }
  st.counters["rtf"] = benchmark::Counter(robot.controlPeriodSeconds(), benchmark::Counter::kIsIterationInvariantRate);
}

// The robot as `centaur simulate stand` builds it when nothing is rendered: without the visual-only geoms, with
// the stand scenario's contact solver.
sim::SimSettings physicsOnly(sim::SimSettings s) {
  s.visual_geoms = false;
  s.solver = "cg";
  return s;
}

void BM_StandClosedLoop(benchmark::State& st) {
  const sim::SimConfig cfg = sim::loadSimConfig("", "", {});
  sim::MujocoRobot robot(physicsOnly(cfg.robot));
  StandingParams params;
  params.use_base_estimator = st.range(0) != 0;
  StandingController ctrl(cfg.robot.model_path, params);
  runLoop(st, robot, ctrl);
}
BENCHMARK(BM_StandClosedLoop)->ArgName("base_estimator")->Arg(1)->Arg(0)->Unit(benchmark::kMicrosecond);

void BM_StandPhysicsAndImpedanceOnly(benchmark::State& st) {
  const sim::SimConfig cfg = sim::loadSimConfig("", "", {});
  sim::MujocoRobot robot(physicsOnly(cfg.robot));
  Eigen::VectorXd q(robot.numJoints());
  robot.jointPositions(q);
  ConstantController ctrl(q);
  runLoop(st, robot, ctrl);
}
BENCHMARK(BM_StandPhysicsAndImpedanceOnly)->Unit(benchmark::kMicrosecond);

void BM_StandingControllerTick(benchmark::State& st) {
  const sim::SimConfig cfg = sim::loadSimConfig("", "", {});
  sim::MujocoRobot robot(physicsOnly(cfg.robot));
  StandingController ctrl(cfg.robot.model_path, StandingParams{});
  RobotState state;
  state.resize(robot.numJoints());
  JointCommand command;
  robot.read(state);
  ctrl.start(state, command);
  for (auto _ : st) {
    ctrl.tick(state, command);
    benchmark::DoNotOptimize(command.tau_ff.data());
  }
}
BENCHMARK(BM_StandingControllerTick)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
