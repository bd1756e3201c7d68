#pragma once
// Stabilizer factory for the jump scenarios: mode "none" | "raibert" | "angmom" | "ocp".
// Reads (and validates) the sections `raibert:`, `angmom:` and `ocp:` of the given reader whichever mode is
// chosen, so a typo in an unused section is still an error.
#include <functional>
#include <memory>
#include <string>

#include "data/arm_trajectory.hpp"
#include "stabilizers/stabilizer.hpp"

namespace centaur {

class YamlReader;

/// The documented defaults of the three stabilizer sections (YAML, indented by two spaces for `controller:`).
std::string stabilizerDefaultsYaml();
/// Supplies an arm-flywheel plan when neither --flywheel nor `ocp.flywheel_file` names one (e.g. the sim layer
/// plans it with the defaults); the stabilizers themselves never plan.
using FlywheelSource = std::function<std::shared_ptr<const data::ArmTrajectory>()>;

/// Throws InputError for an unknown mode or a bad key (naming it). flywheel_file (mode "ocp"): the arm-flywheel
/// plan (HDF5, `centaur plan arm-flywheel`); empty = the `ocp.flywheel_file` key, else `fallback()`; InputError
/// if all three are empty.
std::unique_ptr<Stabilizer> makeStabilizer(const std::string& mode, YamlReader& section,
                                           const std::string& flywheel_file = "", const FlywheelSource& fallback = {});

}  // namespace centaur
