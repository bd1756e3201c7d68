// Fuzz target: the planner's configuration loaders (planner/jump_config.hpp for both jumps, arm_flywheel_config.hpp):
// the input is a configuration file followed by NUL-separated --set overrides, loaded exactly as `centaur plan
// --config F --set ...` loads them (defaults <- file <- overrides, every key and consistency rule checked).
#include "fuzz_support.hpp"
#include "planner/arm_flywheel_config.hpp"
#include "planner/jump_config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const int which = data[0] % 3;  // first byte: squat-jump, half-squat-jump, arm-flywheel
  std::vector<std::string> parts = centaur_fuzz::splitNul(data + 1, size - 1, 5);
  const std::string file = centaur_fuzz::scratchFile(parts[0], ".yaml");
  const std::vector<std::string> overrides(parts.begin() + 1, parts.end());
  centaur_fuzz::expectOnlyInputErrors([&] {
    if (which == 2) {
      centaur::planner::loadArmFlywheelConfig(file, overrides);
    } else {
      centaur::planner::loadJumpConfig(which == 0 ? "squat-jump" : "half-squat-jump", file, overrides);
    }
  });
  return 0;
}
