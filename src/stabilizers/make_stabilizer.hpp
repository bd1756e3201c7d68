#pragma once
// Stabilizer factory for the jump scenarios: mode "none" | "raibert" | "angmom" | "ocp".
// Reads (and validates) the sections `raibert:`, `angmom:` and `ocp:` of the given reader whichever mode is
// chosen, so a typo in an unused section is still an error.
#include <memory>
#include <string>

#include "stabilizers/stabilizer.hpp"

namespace centaur {

class YamlReader;

/// The documented defaults of the three stabilizer sections (YAML, indented by two spaces for `controller:`).
std::string stabilizerDefaultsYaml();
/// Throws InputError for an unknown mode or a bad key (naming it). flywheel_file (mode "ocp"): the arm-flywheel
/// plan (HDF5, `centaur plan arm-flywheel`); empty = the `ocp.flywheel_file` key, or planned now with defaults.
std::unique_ptr<Stabilizer> makeStabilizer(const std::string& mode, YamlReader& section,
                                           const std::string& flywheel_file = "");

}  // namespace centaur
