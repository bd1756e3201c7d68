// Fuzz target: the simulation's scenario configuration (sim/sim_config.hpp) as `centaur simulate <scenario> --config
// F --set ...` loads it, for the scenario chosen by the first byte (its defaults merged first).
#include "fuzz_support.hpp"
#include "sim/scenario.hpp"
#include "sim/sim_config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const auto& all = centaur::sim::scenarios();
  const centaur::sim::Scenario& scenario = all[data[0] % all.size()];
  std::vector<std::string> parts = centaur_fuzz::splitNul(data + 1, size - 1, 5);
  const std::string file = centaur_fuzz::scratchFile(parts[0], ".yaml");
  const std::vector<std::string> overrides(parts.begin() + 1, parts.end());
  centaur_fuzz::expectOnlyInputErrors([&] {
    const centaur::sim::SimConfig config = centaur::sim::loadSimConfig(scenario.defaults_yaml, file, overrides);
    centaur::sim::controllerSection(config);
  });
  return 0;
}
