#pragma once
// The arm-flywheel plan with the embedded defaults, planned on demand for `simulate --stabilizer ocp` without
// --flywheel (the stabilizer itself never plans). Computed once per process (thread-safe) and shared.
#include <memory>

#include "data/arm_trajectory.hpp"

namespace centaur::sim {

/// Plans (~1-3 s) at the first call; RuntimeError if the default plan does not converge.
std::shared_ptr<const data::ArmTrajectory> defaultArmFlywheel();

}  // namespace centaur::sim
