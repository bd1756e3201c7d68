// The `stand` scenario: keep the home posture on flat ground (StandingController).
#include "controller/standing_controller.hpp"
#include "sim/scenario.hpp"

namespace centaur::sim {

Scenario standScenario() {
  Scenario s;
  s.name = "stand";
  s.help = "keep the home posture on flat ground: joint impedance + gravity-compensating feed-forward";
  // Standing: CG is the fastest contact solver for four resting wheels (Newton pays a factorisation per step).
  s.defaults_yaml = std::string("duration: 10.0\nphysics: {solver: cg}\n") + StandingParams::defaultsYaml();
  s.make_controller = [](ScenarioContext& ctx) -> std::unique_ptr<Controller> {
    StandingParams params;
    params.read(ctx.controller_config);
    ctx.controller_config.finish();
    auto controller = std::make_unique<StandingController>(ctx.config.robot.model_path, params);
    if (controller->model().jointNames() != ctx.robot.jointNames()) {
      throw InputError(ctx.config.robot.model_path +
                       ": the controller model's joint order differs from the simulator's actuator order");
    }
    return controller;
  };
  return s;
}

}  // namespace centaur::sim
