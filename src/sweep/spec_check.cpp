#include "sweep/spec_check.hpp"

#include <regex>

#include "common/error.hpp"
#include "common/number_text.hpp"
#include "common/yaml_reader.hpp"
#include "planner/jump_config.hpp"
#include "sim/scenario.hpp"
#include "sim/sim_config.hpp"
#include "sweep/yaml_values.hpp"

namespace centaur::sweep {

namespace {

/// (jump index, one value index per axis) of a grid point; the last axis varies fastest.
std::vector<std::size_t> decompose(const SweepSpec& spec, std::size_t point, std::size_t& jump) {
  std::vector<std::size_t> at(spec.axes.size(), 0);
  for (std::size_t a = spec.axes.size(); a-- > 0;) {
    const std::size_t n = spec.axes[a].values.size();
    at[a] = point % n;
    point /= n;
  }
  jump = point;
  return at;
}

std::vector<std::string> assignments(const std::map<std::string, std::string>& set) {
  std::vector<std::string> out;
  for (const auto& [k, v] : set) out.push_back(k + "=" + v);
  return out;
}

const sim::Scenario& scenarioOf(const std::string& jump) {
  const sim::Scenario* s = sim::findScenario(jump);
  if (s == nullptr) throw RuntimeError("the jump scenario '" + jump + "' is not registered");
  return *s;
}

/// Parses the simulation configuration of `jump` with `overrides` as a run would; InputError(file, key) if not.
void checkRunConfig(const SweepSpec& spec, const std::string& jump, const std::vector<std::string>& overrides,
                    const std::string& key, const std::string& what) {
  const sim::Scenario& s = scenarioOf(jump);
  try {
    const sim::SimConfig config = sim::loadSimConfig(s.defaults_yaml, "", overrides);
    YamlReader controller = sim::controllerSection(config);
    if (s.check_controller) s.check_controller(controller);
  } catch (const InputError& e) {
    throw InputError(spec.file, key, what + e.what());
  }
}

}  // namespace

SimKeyShape simKeyShape(const SweepSpec& spec, const std::string& key) {
  const std::string where = "simulation.perturb." + key;
  const sim::Scenario& s = scenarioOf(spec.jumps.front());
  YAML::Node node = mergeYaml(loadYamlString(sim::kSimConfigDefaults, "<simulation defaults>"),
                              loadYamlString(s.defaults_yaml, "<scenario defaults>"));
  std::size_t begin = 0;
  while (true) {
    const std::size_t dot = key.find('.', begin);
    const std::string part = key.substr(begin, dot == std::string::npos ? std::string::npos : dot - begin);
    if (!node.IsMap() || !node[part]) {
      throw InputError(spec.file, where, "no such simulation key (the keys and their ranges: docs/sim.md)");
    }
    node = node[part];
    if (dot == std::string::npos) break;
    begin = dot + 1;
  }
  SimKeyShape shape;
  if (node.IsMap()) throw InputError(spec.file, where, "is a section; give one of its keys");
  if (node.IsSequence()) {
    shape.size = static_cast<int>(node.size());
    if (shape.size < 1) throw InputError(spec.file, where, "an empty list cannot be sampled");
    return shape;
  }
  const std::string text = node.IsScalar() ? node.Scalar() : std::string();
  static const std::regex integer("^[-+]?[0-9]+$"), real("^[-+]?([0-9]+\\.?[0-9]*|\\.[0-9]+)([eE][-+]?[0-9]+)?$");
  shape.integer = std::regex_match(text, integer);
  if (!shape.integer && !std::regex_match(text, real)) {
    throw InputError(spec.file, where, "is not numeric (default '" + text + "'): give it in simulation.set");
  }
  return shape;
}

std::vector<std::string> plannerOverrides(const SweepSpec& spec, std::size_t point) {
  std::size_t jump = 0;
  const std::vector<std::size_t> at = decompose(spec, point, jump);
  std::vector<std::string> out = assignments(spec.planner_set);
  for (std::size_t a = 0; a < spec.axes.size(); ++a) out.push_back(spec.axes[a].key + "=" + spec.axes[a].values[at[a]].yaml());
  return out;
}

const std::string& pointJump(const SweepSpec& spec, std::size_t point) {
  std::size_t jump = 0;
  decompose(spec, point, jump);
  return spec.jumps.at(jump);
}

std::vector<data::GridValue> pointValues(const SweepSpec& spec, std::size_t point) {
  std::size_t jump = 0;
  const std::vector<std::size_t> at = decompose(spec, point, jump);
  std::vector<data::GridValue> out;
  for (std::size_t a = 0; a < spec.axes.size(); ++a) out.push_back(spec.axes[a].values[at[a]]);
  return out;
}

void checkPlanner(const SweepSpec& spec) {
  const std::vector<std::string> base = assignments(spec.planner_set);
  for (const std::string& jump : spec.jumps) {
    try {
      planner::loadJumpConfig(jump, "", base);
    } catch (const InputError& e) {
      throw InputError(spec.file, "planner.set", jump + ": " + e.what());
    }
    for (const Axis& axis : spec.axes) {  // each value alone first: the message names its axis
      for (const auto& v : axis.values) {
        std::vector<std::string> o = base;
        o.push_back(axis.key + "=" + v.yaml());
        try {
          planner::loadJumpConfig(jump, "", o);
        } catch (const InputError& e) {
          throw InputError(spec.file, "planner.axes." + axis.key, jump + ", value " + v.yaml() + ": " + e.what());
        }
      }
    }
  }
  for (std::size_t p = 0; p < spec.points(); ++p) {  // then every combination
    const std::vector<std::string> o = plannerOverrides(spec, p);
    try {
      planner::loadJumpConfig(pointJump(spec, p), "", o);
    } catch (const InputError& e) {
      std::string point;
      for (std::size_t i = base.size(); i < o.size(); ++i) point += (point.empty() ? "" : ", ") + o[i];
      throw InputError(spec.file, "planner.axes", pointJump(spec, p) + " at " + point + ": " + e.what());
    }
  }
}

void checkSimulation(const SweepSpec& spec) {
  const std::vector<std::string> base = assignments(spec.simulation_set);
  for (const std::string& jump : spec.jumps) {
    checkRunConfig(spec, jump, base, "simulation.set", jump + ": ");
    for (const Distribution& d : spec.perturb) {
      std::vector<std::vector<double>> extremes;
      if (d.kind == Distribution::Kind::kUniform) extremes = {d.a, d.b};
      if (d.kind == Distribution::Kind::kNormal) extremes = {d.a};
      if (!d.clip_lo.empty()) extremes.insert(extremes.end(), {d.clip_lo, d.clip_hi});
      if (d.kind == Distribution::Kind::kChoice) extremes = d.choices;
      for (const auto& v : extremes) {
        std::vector<std::string> o = base;
        o.push_back(d.key + "=" + numbersText(v));
        checkRunConfig(spec, jump, o, "simulation.perturb." + d.key, jump + ", value " + numbersText(v) + ": ");
      }
    }
  }
}

}  // namespace centaur::sweep
