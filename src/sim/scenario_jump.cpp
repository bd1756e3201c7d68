// The jump scenarios (issue 5 item 5): `squat-jump` and `half-squat-jump`, a planned primitive replayed on
// CENTAURO by the JumpController with one of the upper-body stabilizers.
//   options: --primitive F.h5  (the group named like the scenario; absent -> planned now with the defaults)
//            --stabilizer none|raibert|angmom|ocp
// Metrics and outcome: JumpObserver (jump_observer.hpp).
#include <cstdio>

#include "common/error.hpp"
#include "common/yaml_reader.hpp"
#include "data/primitive_io.hpp"
#include "planner/jump_problem.hpp"
#include "sim/default_arm_flywheel.hpp"
#include "sim/jump_observer.hpp"
#include "sim/scenario.hpp"
#include "stabilizers/jump_controller.hpp"
#include "stabilizers/make_stabilizer.hpp"

namespace centaur::sim {

namespace {

data::Primitive loadOrPlan(const std::string& name, const std::string& file) {
  if (!file.empty()) return data::readPrimitive(file, name);
  std::fprintf(stderr, "planning %s with the default settings (give --primitive F.h5 to reuse a plan) ...\n",
               name.c_str());
  const planner::JumpConfig cfg = planner::loadJumpConfig(name, "", {});
  const planner::JumpProblem problem(cfg);
  const planner::SolveResult result = problem.solve(false);
  if (!result.info.solved()) {
    throw RuntimeError("planning " + name + " did not converge (" + result.info.status + ")");
  }
  return problem.toPrimitive(result);
}

Scenario jumpScenario(const std::string& name, JumpKind kind, double duration, const std::string& extra_defaults,
                      const std::string& help) {
  Scenario s;
  s.name = name;
  s.help = help;
  s.defaults_yaml = "duration: " + std::to_string(duration) + "\n" + JumpControllerParams::defaultsYaml() +
                    stabilizerDefaultsYaml();
  s.defaults_yaml = toYamlString(mergeYaml(loadYamlString(s.defaults_yaml, name), loadYamlString(extra_defaults, name)));
  s.options = {{"primitive", "primitive database (HDF5) holding the group '" + name + "' (default: plan it now)",
                "", {}, false, true},
               {"stabilizer", "upper-body stabilizer", "none", {"none", "raibert", "angmom", "ocp"}, false},
               {"flywheel", "arm-flywheel plan (HDF5) for --stabilizer ocp (default: plan it now)", "", {}, false,
                true}};
  s.make_controller = [name](ScenarioContext& ctx) -> std::unique_ptr<Controller> {
    JumpControllerParams params;
    params.read(ctx.controller_config);
    std::unique_ptr<Stabilizer> stabilizer = makeStabilizer(ctx.options.at("stabilizer"), ctx.controller_config,
                                                           ctx.options.at("flywheel"), defaultArmFlywheel);
    ctx.controller_config.finish();
    params.wbc.dt = ctx.robot.controlPeriodSeconds();
    const data::Primitive primitive = loadOrPlan(name, ctx.options.at("primitive"));
    auto controller = std::make_unique<JumpController>(ctx.config.robot.model_path, primitive, std::move(stabilizer),
                                                       params);
    if (controller->wholeBody().ikModel().jointNames() != ctx.robot.jointNames()) {
      throw InputError(ctx.config.robot.model_path +
                       ": the controller model's joint order differs from the simulator's actuator order");
    }
    return controller;
  };
  s.make_observer = [kind](ScenarioContext& ctx) -> std::unique_ptr<RunObserver> {
    JumpObserverParams p;
    p.kind = kind;
    const YAML::Node settle = ctx.config.effective["controller"]["settle_time"];
    p.primitive_start = settle ? settle.as<double>() : 0.5;
    return std::make_unique<JumpObserver>(ctx.robot, p);
  };
  return s;
}

}  // namespace

Scenario squatJumpScenario() {
  // No wall (it is behind the robot for the half-squat jump only); after landing, stand up again.
  return jumpScenario("squat-jump", JumpKind::kSquat, 5.0,
                      "world: {wall_x: -20.0}\ncontroller: {recover_time: 1.0, ocp: {blend_time: 0.45}}\n",
                      "replay a squat-jump primitive (all four wheels take off and land) with an upper-body stabilizer");
}

Scenario halfSquatJumpScenario() {
  return jumpScenario("half-squat-jump", JumpKind::kHalfSquat, 6.5, "controller: {ocp: {blend_time: 0.45}}\n",
                      "replay a half-squat-jump primitive (rear wheels onto the wall behind) with an upper-body stabilizer");
}

}  // namespace centaur::sim
