#include "sim/scenario.hpp"

namespace centaur::sim {

std::vector<Scenario>& scenarios() {
  static std::vector<Scenario> registry{standScenario(), squatJumpScenario(), halfSquatJumpScenario()};
  return registry;
}

const Scenario* findScenario(const std::string& name) {
  for (const auto& s : scenarios()) {
    if (s.name == name) return &s;
  }
  return nullptr;
}

}  // namespace centaur::sim
