#pragma once
// The specification of a sweep (`centaur sweep SPEC.yaml`, docs/sweeps.md): which jumps and stabilizer modes,
// the planner axes (planner keys, each a list or a range of values: their product is the grid of primitives),
// the simulation overrides of every run and the perturbations sampled per run, the seeds per grid point and the
// heatmaps to draw. Strict: unknown keys, empty axes, reversed ranges, unknown modes, bad seeds, planner or
// simulation keys that do not exist and values out of their ranges are InputError naming the spec file and the
// key (CLI exit code 2), found before anything is written.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "data/primitive_database.hpp"

namespace centaur::sweep {

/// One planner axis: a planner key and its values (all numbers or all strings).
struct Axis {
  std::string key;  ///< dotted planner key, e.g. target.height
  std::vector<data::GridValue> values;
  bool numeric() const { return values.empty() || values.front().numeric; }
};

/// How one simulation key is sampled per run.
struct Distribution {
  enum class Kind { kUniform, kNormal, kChoice };
  std::string key;              ///< dotted simulation key, e.g. world.friction
  Kind kind = Kind::kUniform;
  int size = 1;                 ///< values per sample: 1 for a scalar key, n for a list key (e.g. 3: com_offset)
  bool integer = false;         ///< the key takes integers (uniform: every integer in [a, b] equally likely)
  std::vector<double> a, b;     ///< uniform: [lo, hi]; normal: [mean, std] (each of `size` values)
  std::vector<double> clip_lo, clip_hi;    ///< normal: optional clip bounds (empty: none)
  std::vector<std::vector<double>> choices;  ///< choice: the candidate values (each of `size` values)
};

struct SweepSpec {
  std::string file;                     ///< where it was read (messages)
  std::vector<std::string> jumps;       ///< squat-jump | half-squat-jump
  std::vector<std::string> modes;       ///< none | raibert | angmom | ocp
  int seeds = 1;                        ///< runs per (grid point, mode), each with its own perturbation sample
  std::int64_t seed = 1;                ///< base seed of the sweep
  std::map<std::string, std::string> planner_set;     ///< planner key -> YAML value, every grid point
  std::vector<Axis> axes;               ///< the grid (the last axis varies fastest)
  std::map<std::string, std::string> simulation_set;  ///< simulation key -> YAML value, every run
  std::vector<Distribution> perturb;    ///< sorted by key
  std::vector<std::pair<std::string, std::string>> heatmaps;  ///< pairs of axis keys (x, y)

  /// The spec in canonical form (sorted keys, ranges expanded to their values, numbers exact): two specs run the
  /// same sweep iff their canonical texts are equal (what `--out` of an existing sweep is checked against).
  std::string canonicalYaml() const;
  std::size_t points() const;  ///< grid points: jumps x the product of the axes' sizes
  std::size_t runs() const { return points() * static_cast<std::size_t>(seeds) * modes.size(); }
};

/// Reads and validates `path` completely (planner and simulation keys included; see the header comment).
SweepSpec loadSweepSpec(const std::string& path);
/// The same from YAML text (`label` names it in messages), e.g. a spec received by an MPI rank.
SweepSpec parseSweepSpec(const std::string& text, const std::string& label);

}  // namespace centaur::sweep
