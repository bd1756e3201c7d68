#include "stabilizers/online_stage.hpp"

#include <algorithm>

#include "common/error.hpp"
#include "common/yaml_reader.hpp"
#include "controller/standing_controller.hpp"
#include "stabilizers/jump_controller.hpp"

namespace centaur {

const std::vector<std::string>& onlineTasks() {
  static const std::vector<std::string> tasks = {"stand", "squat-jump", "half-squat-jump"};
  return tasks;
}

bool isJumpTask(const std::string& task) { return task == "squat-jump" || task == "half-squat-jump"; }

std::string controllerDefaultsYaml(const std::string& task) {
  if (task == "stand") return StandingParams::defaultsYaml();
  if (!isJumpTask(task)) {
    throw InputError("task '" + task + "' is not available (stand, squat-jump, half-squat-jump)");
  }
  const std::string common = JumpControllerParams::defaultsYaml() + stabilizerDefaultsYaml();
  // Per task: the squat jump stands up again after landing; both arm blends end within the 0.5 s settle time.
  const std::string task_yaml = task == "squat-jump" ? "controller: {recover_time: 1.0, ocp: {blend_time: 0.45}}\n"
                                                     : "controller: {ocp: {blend_time: 0.45}}\n";
  return toYamlString(mergeYaml(loadYamlString(common, task), loadYamlString(task_yaml, task)));
}

std::unique_ptr<SupervisedController> makeOnlineController(const std::string& task, YamlReader& section,
                                                           const OnlineStageInputs& in) {
  if (task == "stand") {
    StandingParams params;
    params.frames = in.frames;  // before read(): the robot's impedance groups are the keys of controller.gains
    params.read(section);
    section.finish();
    return std::make_unique<StandingController>(in.model_path, params);
  }
  if (!isJumpTask(task)) {
    throw InputError("task '" + task + "' is not available (stand, squat-jump, half-squat-jump)");
  }
  JumpControllerParams params;
  params.wbc.frames = in.frames;
  params.wbc.impedance.frames = in.frames;  // before read(): the robot's impedance groups are the keys of gains
  params.read(section);
  std::unique_ptr<Stabilizer> stabilizer = makeStabilizer(in.stabilizer, section, in.flywheel_file,
                                                         in.flywheel_fallback);
  section.finish();  // unknown keys are refused before a primitive is loaded (or planned by the caller)
  params.wbc.dt = in.dt;
  if (!in.primitive) throw InputError(task + ": no primitive to replay (give --primitive F.h5)");
  const data::Primitive primitive = in.primitive();
  return std::make_unique<JumpController>(in.model_path, primitive, std::move(stabilizer), params);
}

}  // namespace centaur
