// The `stand` scenario: keep the home posture on flat ground (StandingController).
#include "controller/standing_controller.hpp"
#include "sim/scenario.hpp"
#include "stabilizers/online_stage.hpp"

namespace centaur::sim {

Scenario standScenario() {
  Scenario s;
  s.name = "stand";
  s.help = "keep the home posture on flat ground: joint impedance + gravity-compensating feed-forward";
  // Standing: CG is the fastest contact solver for four resting wheels (Newton pays a factorisation per step).
  s.defaults_yaml = std::string("duration: 10.0\nphysics: {solver: cg}\n") + controllerDefaultsYaml("stand");
  s.make_controller = [](ScenarioContext& ctx) -> std::unique_ptr<Controller> {
    OnlineStageInputs in;
    in.model_path = ctx.config.robot.model_path;
    in.frames = ctx.config.frames;
    in.dt = ctx.robot.controlPeriodSeconds();
    auto controller = makeOnlineController("stand", ctx.controller_config, in);
    if (static_cast<const StandingController&>(*controller).model().jointNames() != ctx.robot.jointNames()) {
      throw InputError(ctx.config.robot.model_path +
                       ": the controller model's joints differ from the simulator's motor-driven joints (a joint without a motor?)");
    }
    return controller;
  };
  return s;
}

}  // namespace centaur::sim
