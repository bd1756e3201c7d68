// The jump scenarios: `squat-jump` and `half-squat-jump`, a planned primitive replayed on
// CENTAURO by the JumpController with one of the upper-body stabilizers.
//   options: --primitive F.h5  (the group named like the scenario; absent -> planned now with the defaults)
//            --primitive-group NAME (another group of that file, e.g. a grid point of a sweep database)
//            --stabilizer none|raibert|angmom|ocp
// Metrics and outcome: JumpObserver (jump_observer.hpp).
#include <cstdio>

#include "common/error.hpp"
#include "common/yaml_reader.hpp"
#include "data/primitive_io.hpp"
#include "planner/jump_problem.hpp"
#include "robot/robot_registry.hpp"
#include "sim/default_arm_flywheel.hpp"
#include "sim/jump_observer.hpp"
#include "sim/scenario.hpp"
#include "stabilizers/jump_controller.hpp"
#include "stabilizers/online_stage.hpp"

namespace centaur::sim {

namespace {

data::Primitive loadOrPlan(const std::string& name, const std::string& file, const std::string& group,
                           const std::string& robot_name) {
  if (!group.empty() && file.empty()) throw InputError("--primitive-group " + group + ": needs --primitive F.h5");
  if (!file.empty()) {
    const std::string g = group.empty() ? name : group;
    data::Primitive p = data::readPrimitive(file, g);
    data::requirePlannedFor(p, robot_name, file + ", group '" + g + "'");
    return p;
  }
  std::fprintf(stderr, "planning %s with the default settings (give --primitive F.h5 to reuse a plan) ...\n",
               name.c_str());
  // The default robot needs no override (the plan's configuration then reads "<defaults>", as it always has).
  const std::vector<std::string> sets =
      robot_name == robot::kDefaultRobot ? std::vector<std::string>{} : std::vector<std::string>{"robot=" + robot_name};
  const planner::JumpConfig cfg = planner::loadJumpConfig(name, "", sets);
  const planner::JumpProblem problem(cfg);
  const planner::SolveResult result = problem.solve(false);
  if (!result.info.solved()) {
    throw RuntimeError("planning " + name + " did not converge (" + result.info.status + ")");
  }
  return problem.toPrimitive(result);
}

Scenario jumpScenario(const std::string& name, JumpKind kind, double duration, const std::string& world_defaults,
                      const std::string& help) {
  Scenario s;
  s.name = name;
  s.help = help;
  s.defaults_yaml = "duration: " + std::to_string(duration) + "\n" + world_defaults;
  s.defaults_yaml = toYamlString(mergeYaml(loadYamlString(s.defaults_yaml, name),
                                           loadYamlString(controllerDefaultsYaml(name), name)));
  s.options = {{"primitive", "primitive database (HDF5) holding the group '" + name + "' (default: plan it now)",
                "", {}, false, true},
               {"stabilizer", "upper-body stabilizer", "none", {"none", "raibert", "angmom", "ocp"}, false},
               {"flywheel", "arm-flywheel plan (HDF5) for --stabilizer ocp (default: plan it now)", "", {}, false,
                true},
               {"primitive-group", "group of the --primitive file to replay (default: the one named like the jump)",
                "", {}, false}};
  s.make_controller = [name](ScenarioContext& ctx) -> std::unique_ptr<Controller> {
    if (ctx.options.at("stabilizer") == "ocp" && ctx.config.robot_name != robot::kDefaultRobot) {
      throw InputError("simulate " + name + " --stabilizer ocp: robot '" + ctx.config.robot_name +
                       "': the arm-flywheel plan is for CENTAURO's 7-DoF arm only so far (none, raibert, angmom run "
                       "every robot)");
    }
    OnlineStageInputs in;
    in.model_path = ctx.config.robot.model_path;
    in.frames = ctx.config.frames;
    in.dt = ctx.robot.controlPeriodSeconds();
    in.stabilizer = ctx.options.at("stabilizer");
    in.flywheel_file = ctx.options.at("flywheel");
    in.flywheel_fallback = defaultArmFlywheel;
    const std::string file = ctx.options.at("primitive");
    const std::string group = ctx.options.at("primitive-group");
    const std::string robot_name = ctx.config.robot_name;
    in.primitive = [name, file, group, robot_name] { return loadOrPlan(name, file, group, robot_name); };
    auto controller = makeOnlineController(name, ctx.controller_config, in);
    const auto& jump = static_cast<const JumpController&>(*controller);
    if (jump.wholeBody().ikModel().jointNames() != ctx.robot.jointNames()) {
      throw InputError(ctx.config.robot.model_path +
                       ": the controller model's joints differ from the simulator's motor-driven joints (a joint without a motor?)");
    }
    return controller;
  };
  s.check_controller = [](YamlReader& controller_config) {
    JumpControllerParams params;
    params.read(controller_config);
    makeStabilizer("none", controller_config);  // reads every stabilizer section; builds nothing for "none"
    controller_config.finish();
  };
  s.make_observer = [kind](ScenarioContext& ctx) -> std::unique_ptr<RunObserver> {
    JumpObserverParams p;
    p.kind = kind;
    p.rear_left = ctx.config.robot.contact_bodies[2];
    p.rear_right = ctx.config.robot.contact_bodies[3];
    const YAML::Node settle = ctx.config.effective["controller"]["settle_time"];
    p.primitive_start = settle ? settle.as<double>() : 0.5;
    return std::make_unique<JumpObserver>(ctx.robot, p);
  };
  return s;
}

}  // namespace

Scenario squatJumpScenario() {
  // No wall (it is behind the robot for the half-squat jump only); after landing, stand up again.
  return jumpScenario("squat-jump", JumpKind::kSquat, 5.0, "world: {wall_x: -20.0}\n",
                      "replay a squat-jump primitive (all four wheels take off and land) with an upper-body stabilizer");
}

Scenario halfSquatJumpScenario() {
  return jumpScenario("half-squat-jump", JumpKind::kHalfSquat, 6.5, "",
                      "replay a half-squat-jump primitive (rear wheels onto the wall behind) with an upper-body stabilizer");
}

}  // namespace centaur::sim
