#include "sweep/sweep_spec.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>

#include "common/error.hpp"
#include "common/number_text.hpp"
#include "common/yaml_reader.hpp"
#include "sweep/results_file.hpp"
#include "sweep/spec_check.hpp"
#include "sweep/yaml_values.hpp"

namespace centaur::sweep {

namespace {

const std::vector<std::string> kJumps = {"squat-jump", "half-squat-jump"};
const std::vector<std::string> kModes = {"none", "raibert", "angmom", "ocp"};
constexpr std::size_t kMaxPoints = 100000;
constexpr std::size_t kMaxRuns = 100000000;

std::string join(const std::vector<std::string>& v, const char* sep = ", ") {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : sep) + x;
  return s;
}

/// A required, non-empty list of distinct names from `allowed`.
std::vector<std::string> nameList(const YAML::Node& node, const std::vector<std::string>& allowed,
                                  const std::string& file, const std::string& key) {
  const std::string expect = "expected a non-empty list of distinct values from: " + join(allowed);
  if (!node || node.IsNull()) throw InputError(file, key, "missing (" + expect + ")");
  if (!node.IsSequence() || node.size() == 0) throw InputError(file, key, expect);
  std::vector<std::string> out;
  for (const auto& n : node) {
    const std::string v = n.IsScalar() ? n.Scalar() : std::string();
    if (std::find(allowed.begin(), allowed.end(), v) == allowed.end()) {
      throw InputError(file, key, "'" + v + "' is not one of: " + join(allowed));
    }
    if (std::find(out.begin(), out.end(), v) != out.end()) throw InputError(file, key, "'" + v + "' is listed twice");
    out.push_back(v);
  }
  return out;
}

/// key -> normalised value text of a mapping of dotted keys (planner.set, simulation.set).
std::map<std::string, std::string> settings(const YAML::Node& node, const std::string& file, const std::string& key) {
  std::map<std::string, std::string> out;
  if (!node || node.IsNull()) return out;
  if (!node.IsMap()) throw InputError(file, key, "expected a mapping of dotted keys to values");
  for (const auto& kv : node) {
    const std::string k = kv.first.as<std::string>();
    checkKeyName(k, file, key + "." + k);
    out[k] = valueText(kv.second, file, key + "." + k);
  }
  return out;
}

/// {from, to, steps} or {from, to, step}.
std::vector<data::GridValue> rangeValues(const YAML::Node& node, const std::string& file, const std::string& key) {
  YamlReader r(node, file, key);
  if (!r.has("from") || !r.has("to")) r.fail("from", "a range needs from, to and steps (or step)");
  double from = 0.0, to = 0.0, step = 0.0;
  int steps = 0;
  r.get("from", from, -1e9, 1e9);
  r.get("to", to, -1e9, 1e9);
  if (r.has("steps") == r.has("step")) r.fail("steps", "give exactly one of steps (the number of values) and step");
  r.get("steps", steps, 1, 100000);
  r.get("step", step, 1e-12, 1e9);
  r.finish();
  if (from > to) throw InputError(file, key, "reversed range: from " + exactNumber(from) + " > to " + exactNumber(to));
  if (r.has("step")) {
    const double count = std::floor((to - from) / step + 1e-9) + 1.0;  // checked before it becomes an int
    if (count > 100000.0) throw InputError(file, key + ".step", "more than 100000 values");
    steps = static_cast<int>(count);
  }
  if (steps == 1 && from != to) throw InputError(file, key + ".steps", "1 value needs from == to; give steps >= 2");
  std::vector<data::GridValue> out;
  for (int i = 0; i < steps; ++i) {
    data::GridValue v;
    const double x = r.has("step") ? from + i * step : (steps == 1 ? from : from + (to - from) * i / (steps - 1));
    char text[32];  // 12 significant digits: 0.15, not 0.15000000000000002 (values are typed in --select)
    std::snprintf(text, sizeof text, "%.12g", x);
    v.number = i == steps - 1 && r.has("steps") ? to : std::strtod(text, nullptr);
    out.push_back(v);
  }
  return out;
}

Axis parseAxis(const std::string& k, const YAML::Node& node, const std::string& file) {
  const std::string key = "planner.axes." + k;
  checkKeyName(k, file, key);
  Axis axis;
  axis.key = k;
  if (node.IsMap()) {
    axis.values = rangeValues(node, file, key);
  } else if (node.IsSequence()) {
    if (node.size() == 0) throw InputError(file, key, "empty axis: give at least one value");
    for (std::size_t i = 0; i < node.size(); ++i) {
      data::GridValue v;
      if (!node[i].IsScalar()) throw InputError(file, key, "axis values must be numbers or strings (not lists)");
      v.numeric = scalarNumber(node[i], v.number);
      if (!v.numeric) {
        v.text = node[i].Scalar();
        checkKeyName(v.text, file, key);
      }
      if (!axis.values.empty() && axis.values.front().numeric != v.numeric) {
        throw InputError(file, key, "mixes numbers and strings");
      }
      axis.values.push_back(v);
    }
  } else {
    throw InputError(file, key, "expected a list of values or a range {from, to, steps}");
  }
  std::set<std::string> seen;
  for (const auto& v : axis.values) {
    if (!seen.insert(v.yaml()).second) throw InputError(file, key, "value " + v.yaml() + " is listed twice");
  }
  return axis;
}

Distribution parseDistribution(const SweepSpec& spec, const std::string& k, const YAML::Node& node) {
  const std::string key = "simulation.perturb." + k;
  const std::string& file = spec.file;
  checkKeyName(k, file, key);
  if (!node.IsMap()) {
    throw InputError(file, key, "expected a distribution: {uniform: [lo, hi]}, {normal: [mean, std]} (optionally "
                                "with clip: [lo, hi]) or {choice: [v1, v2, ...]}; fixed values go to simulation.set");
  }
  const SimKeyShape shape = simKeyShape(spec, k);
  Distribution d;
  d.key = k;
  d.size = shape.size;
  d.integer = shape.integer;
  YamlReader r(node, file, key);
  const int kinds = r.has("uniform") + r.has("normal") + r.has("choice");
  if (kinds != 1) r.fail("uniform", "give exactly one of uniform, normal, choice");
  auto pair = [&](const char* name) {
    const YAML::Node p = r.raw(name);
    if (!p.IsSequence() || p.size() != 2) r.fail(name, "expected [a, b]");
    return std::make_pair(numbers(p[0], d.size, true, file, key + "." + name),
                          numbers(p[1], d.size, true, file, key + "." + name));
  };
  if (r.has("uniform")) {
    d.kind = Distribution::Kind::kUniform;
    std::tie(d.a, d.b) = pair("uniform");
    for (int i = 0; i < d.size; ++i) {
      if (d.a[i] > d.b[i]) r.fail("uniform", "reversed range: lower bound above upper bound");
      if (d.integer && (d.a[i] != std::floor(d.a[i]) || d.b[i] != std::floor(d.b[i]))) {
        r.fail("uniform", "an integer key: the bounds must be integers");
      }
    }
  } else if (r.has("normal")) {
    d.kind = Distribution::Kind::kNormal;
    std::tie(d.a, d.b) = pair("normal");
    for (double s : d.b) {
      if (s < 0.0) r.fail("normal", "the standard deviation must be >= 0");
    }
    if (r.has("clip")) {
      std::tie(d.clip_lo, d.clip_hi) = pair("clip");
      for (int i = 0; i < d.size; ++i) {
        if (d.clip_lo[i] > d.clip_hi[i]) r.fail("clip", "reversed range: lower bound above upper bound");
      }
    }
  } else {
    d.kind = Distribution::Kind::kChoice;
    const YAML::Node c = r.raw("choice");
    if (!c.IsSequence() || c.size() == 0) r.fail("choice", "expected a non-empty list of values");
    for (const auto& v : c) d.choices.push_back(numbers(v, d.size, false, file, key + ".choice"));
  }
  if (d.kind != Distribution::Kind::kNormal && r.has("clip")) r.fail("clip", "only a normal distribution is clipped");
  r.finish();
  return d;
}

std::vector<std::pair<std::string, std::string>> parseHeatmaps(const YamlReader& r, const YAML::Node& node,
                                                              const SweepSpec& spec) {
  std::vector<std::pair<std::string, std::string>> out;
  auto isAxis = [&](const std::string& k) {
    return std::any_of(spec.axes.begin(), spec.axes.end(), [&](const Axis& a) { return a.key == k; });
  };
  if (!node || node.IsNull()) {  // default: the first two axes
    if (spec.axes.size() >= 2) out.emplace_back(spec.axes[0].key, spec.axes[1].key);
    return out;
  }
  if (!node.IsSequence()) r.fail("heatmaps", "expected a list of [x axis, y axis] pairs of planner axes");
  for (const auto& p : node) {
    if (!p.IsSequence() || p.size() != 2 || !p[0].IsScalar() || !p[1].IsScalar()) {
      r.fail("heatmaps", "expected a list of [x axis, y axis] pairs of planner axes");
    }
    const std::string x = p[0].Scalar(), y = p[1].Scalar();
    for (const auto& k : {x, y}) {
      if (!isAxis(k)) r.fail("heatmaps", "'" + k + "' is not a planner axis of this sweep");
    }
    if (x == y) r.fail("heatmaps", "a heatmap needs two different axes ('" + x + "' twice)");
    out.emplace_back(x, y);
  }
  return out;
}

void parseStructure(const YAML::Node& root, SweepSpec& spec) {
  const std::string& file = spec.file;
  YamlReader r(root, file);
  spec.jumps = nameList(r.raw("jumps"), kJumps, file, "jumps");
  spec.modes = nameList(r.raw("modes"), kModes, file, "modes");
  r.get("seeds", spec.seeds, 1, 1000000);
  int seed = 1;
  r.get("seed", seed, 0, 2147483647);
  spec.seed = seed;
  {
    auto p = r.child("planner");
    spec.planner_set = settings(p.raw("set"), file, "planner.set");
    const YAML::Node axes = p.raw("axes");
    if (axes && !axes.IsNull() && !axes.IsMap()) p.fail("axes", "expected a mapping: planner key -> values");
    if (axes && axes.IsMap()) {
      for (const auto& kv : axes) {
        const std::string k = kv.first.as<std::string>();
        spec.axes.push_back(parseAxis(k, kv.second, file));
        if (spec.planner_set.count(k)) p.fail("axes." + k, "also given in planner.set");
      }
    }
    p.finish();
  }
  {
    auto s = r.child("simulation");
    spec.simulation_set = settings(s.raw("set"), file, "simulation.set");
    const YAML::Node perturb = s.raw("perturb");
    if (perturb && !perturb.IsNull() && !perturb.IsMap()) s.fail("perturb", "expected a mapping: key -> distribution");
    if (perturb && perturb.IsMap()) {
      for (const auto& kv : perturb) {
        const std::string k = kv.first.as<std::string>();
        if (spec.simulation_set.count(k)) s.fail("perturb." + k, "also given in simulation.set");
        spec.perturb.push_back(parseDistribution(spec, k, kv.second));
      }
    }
    std::sort(spec.perturb.begin(), spec.perturb.end(),
              [](const Distribution& a, const Distribution& b) { return a.key < b.key; });
    for (const std::string k : {"sensors.seed"}) {
      if (spec.simulation_set.count(k) || std::any_of(spec.perturb.begin(), spec.perturb.end(),
                                                      [&](const Distribution& d) { return d.key == k; })) {
        throw InputError(file, "simulation." + k, "is derived per run from the sweep's seed; give `seed` instead");
      }
    }
    s.finish();
  }
  spec.heatmaps = parseHeatmaps(r, r.raw("heatmaps"), spec);
  r.finish();
  if (spec.points() > kMaxPoints) throw InputError(file, "planner.axes", "more than 100000 grid points");
  if (spec.runs() > kMaxRuns) throw InputError(file, "seeds", "more than 1e8 runs");
}

// ---- canonical text ----------------------------------------------------------------------------------

std::string distributionText(const Distribution& d) {
  switch (d.kind) {
    case Distribution::Kind::kUniform:
      return "{uniform: [" + numbersText(d.a) + ", " + numbersText(d.b) + "]}";
    case Distribution::Kind::kNormal: {
      std::string s = "{normal: [" + numbersText(d.a) + ", " + numbersText(d.b) + "]";
      if (!d.clip_lo.empty()) s += ", clip: [" + numbersText(d.clip_lo) + ", " + numbersText(d.clip_hi) + "]";
      return s + "}";
    }
    case Distribution::Kind::kChoice: {
      std::string s = "{choice: [";
      for (std::size_t i = 0; i < d.choices.size(); ++i) s += (i ? ", " : "") + numbersText(d.choices[i]);
      return s + "]}";
    }
  }
  return "";
}

}  // namespace

std::size_t SweepSpec::points() const {
  std::size_t n = jumps.size();
  for (const Axis& a : axes) n *= a.values.size();
  return n;
}

std::string SweepSpec::canonicalYaml() const {
  std::ostringstream s;
  s << "# centaur sweep: the effective specification (canonical form; docs/sweeps.md)\n";
  s << "jumps: [" << join(jumps) << "]\nmodes: [" << join(modes) << "]\nseeds: " << seeds << "\nseed: " << seed
    << "\nplanner:\n  set:" << (planner_set.empty() ? " {}" : "") << "\n";
  for (const auto& [k, v] : planner_set) s << "    " << k << ": " << v << "\n";
  s << "  axes:" << (axes.empty() ? " {}" : "") << "\n";
  for (const Axis& a : axes) {
    std::vector<std::string> values;
    for (const auto& v : a.values) values.push_back(v.yaml());
    s << "    " << a.key << ": [" << join(values) << "]\n";
  }
  s << "simulation:\n  set:" << (simulation_set.empty() ? " {}" : "") << "\n";
  for (const auto& [k, v] : simulation_set) s << "    " << k << ": " << v << "\n";
  s << "  perturb:" << (perturb.empty() ? " {}" : "") << "\n";
  for (const Distribution& d : perturb) s << "    " << d.key << ": " << distributionText(d) << "\n";
  s << "heatmaps: [";
  for (std::size_t i = 0; i < heatmaps.size(); ++i) {
    s << (i ? ", " : "") << "[" << heatmaps[i].first << ", " << heatmaps[i].second << "]";
  }
  s << "]\n";
  return s.str();
}

SweepSpec parseSweepSpec(const std::string& text, const std::string& label) {
  SweepSpec spec;
  spec.file = label;
  const YAML::Node root = loadYamlString(text, label);
  if (!root.IsMap()) throw InputError(label, "<root>", "expected a mapping (jumps, modes, seeds, planner, simulation)");
  parseStructure(root, spec);
  std::set<std::string> columns;  // axis and perturbed keys become results.h5 columns next to the fixed ones
  for (const auto& c : resultsColumns(spec)) {
    if (!columns.insert(c.name).second) throw InputError(label, c.name, "is also the name of another results.h5 column");
  }
  checkPlanner(spec);
  checkSimulation(spec);
  return spec;
}

SweepSpec loadSweepSpec(const std::string& path) {
  loadYamlFile(path);  // InputError naming the file if it is missing or malformed (line and column)
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return parseSweepSpec(text, path);
}

}  // namespace centaur::sweep
