#include "sim/default_arm_flywheel.hpp"

#include <cstdio>
#include <mutex>

#include "common/error.hpp"
#include "planner/arm_flywheel_problem.hpp"

namespace centaur::sim {

std::shared_ptr<const data::ArmTrajectory> defaultArmFlywheel() {
  static std::mutex mutex;
  static std::shared_ptr<const data::ArmTrajectory> plan;
  std::lock_guard<std::mutex> lock(mutex);
  if (!plan) {
    std::fprintf(stderr, "planning the arm flywheel with the default settings (give --flywheel F.h5 to reuse a plan)\n");
    auto tr = std::make_shared<data::ArmTrajectory>(
        planner::planArmFlywheel(planner::loadArmFlywheelConfig("", {})));
    if (!tr->solve.solved()) {
      throw RuntimeError("ocp stabilizer: the default arm-flywheel plan did not converge (" + tr->solve.status +
                         "); plan it with `centaur plan arm-flywheel` and give --flywheel");
    }
    plan = tr;
  }
  return plan;
}

}  // namespace centaur::sim
