#pragma once
// The online stage of each task, built in one place: `centaur simulate` (controller and simulator in one
// process) and the controller node (`centaur control`, over the middleware) run exactly this code.
//
// Tasks: "stand" (StandingController), "squat-jump" and "half-squat-jump" (JumpController: primitive replay +
// whole-body HQP + one upper-body stabilizer). Each task has the documented defaults of its `controller:`
// section; the caller owns everything else (the simulator, or the middleware).
// This layer never plans: a jump's primitive and the arm-flywheel plan come from files or from the caller.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "controller/robot_frames.hpp"
#include "controller/robot_interface.hpp"
#include "data/primitive.hpp"
#include "stabilizers/make_stabilizer.hpp"

namespace centaur {

class YamlReader;

/// "stand", "squat-jump", "half-squat-jump".
const std::vector<std::string>& onlineTasks();
bool isJumpTask(const std::string& task);

/// The documented defaults of a task's `controller:` section (YAML text whose root is `controller:`).
/// InputError for an unknown task.
std::string controllerDefaultsYaml(const std::string& task);

struct OnlineStageInputs {
  std::string model_path;          ///< MJCF of the controller's own robot model
  RobotFrames frames;              ///< the robot's names, radii and impedance groups (default CENTAURO's)
  double dt = 0.001;               ///< [s] control period
  std::string stabilizer = "none"; ///< jumps: none | raibert | angmom | ocp
  std::string flywheel_file;       ///< jumps, ocp: arm-flywheel plan ("" = the `ocp.flywheel_file` key, else fallback)
  FlywheelSource flywheel_fallback;  ///< jumps, ocp: supplies a plan when no file names one (may be empty)
  /// Jumps: the primitive to replay (a group named like the task). Required for jumps.
  std::function<data::Primitive()> primitive;
};

/// Reads the task's whole `controller:` section strictly (finish() included, before any primitive is loaded)
/// and builds its controller. InputError naming the key for bad settings, a missing primitive or plan.
std::unique_ptr<SupervisedController> makeOnlineController(const std::string& task, YamlReader& controller_section,
                                                           const OnlineStageInputs& inputs);

}  // namespace centaur
