#pragma once
// Strict YAML reading: every key must be known, every value inside its documented range.
// A reader wraps one mapping; each get() marks its key as consumed, finish() rejects the rest.
// Errors name the file, the full dotted key and the allowed range (InputError, exit code 2); values and keys
// are quoted as bounded excerpts (common/excerpt.hpp).
//
// Loading is strict too (loadYamlFile, loadYamlString, applyOverride, every configuration of the project goes
// through them): one document, a mapping at the root, unique plain keys (no duplicate, null, alias or
// complex key), and the limits of YamlLimits below, all checked in one streaming pass over the parser's events
// before any tree is built, so an oversized document is refused in time linear in its size.
#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <set>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "common/error.hpp"

namespace centaur {

/// The one place for the size limits of YAML input (configuration files, stacks, --set values).
struct YamlLimits {
  static constexpr std::size_t kMaxBytes = 1 << 20;  ///< a file or text; the shipped configurations are < 8 KiB
  static constexpr std::size_t kMaxNodes = 10000;    ///< keys, values and list items, aliases expanded
  static constexpr int kMaxDepth = 64;               ///< nesting of mappings and lists; --set key segments
  static constexpr std::size_t kMaxUnknownKeysNamed = 5;  ///< finish() names the first ones, then counts
};

class YamlReader {
 public:
  /// `node` must be a mapping (or null: treated as empty). `file` and `prefix` only label messages.
  YamlReader(const YAML::Node& node, std::string file, std::string prefix = "");

  bool has(const std::string& key) const;

  /// Optional keys: if present, read and range-check into `value`; otherwise keep `value` (the default).
  void get(const std::string& key, double& value, double lo, double hi);
  void get(const std::string& key, int& value, int lo, int hi);
  void get(const std::string& key, bool& value);
  void get(const std::string& key, std::string& value, const std::vector<std::string>& allowed = {});
  /// Fixed-size vector (YAML sequence of exactly value.size() numbers), each element in [lo, hi].
  void get(const std::string& key, Eigen::Ref<Eigen::VectorXd> value, double lo, double hi);
  /// [lower, upper] with both in [lo, hi] and lower < upper (InputError naming the key otherwise).
  void getInterval(const std::string& key, Eigen::Vector2d& value, double lo, double hi);
  /// Variable-length vector of numbers, each in [lo, hi].
  void get(const std::string& key, std::vector<double>& value, double lo, double hi);

  /// A list of exactly `count` points [x, y, z], each coordinate in [lo, hi]; `what` describes the list in
  /// messages (e.g. "points in the waist frame (FL, FR, RL, RR)").
  void getPoints(const std::string& key, Eigen::Vector3d* points, int count, double lo, double hi, const std::string& what);

  /// Sub-mapping reader ("a.b"). The key is marked consumed. Missing key -> empty reader.
  YamlReader child(const std::string& key);
  /// The raw node of a key (marked consumed), for sequences of mappings.
  YAML::Node raw(const std::string& key);

  /// Throws InputError naming the first keys that were never read (and how many there are).
  void finish() const;

  const std::string& file() const { return file_; }
  std::string full(const std::string& key) const { return prefix_.empty() ? key : prefix_ + "." + key; }
  [[noreturn]] void fail(const std::string& key, const std::string& message) const;

 private:
  YAML::Node node_;
  std::string file_;
  std::string prefix_;
  std::set<std::string> used_;
};

/// Parse "a.b.c=value" and set it in `root` (creating mappings), the value parsed as YAML.
/// Throws InputError for a malformed assignment.
void applyOverride(YAML::Node& root, const std::string& assignment);

/// Load a YAML configuration file (a mapping; empty = empty mapping); InputError naming the file (and the line
/// and column) if it is missing, not a regular file, larger than the limits, malformed or not strict (above).
YAML::Node loadYamlFile(const std::string& path);

/// Load a YAML mapping from text (embedded defaults, a stack given as text); `label` names it in messages.
YAML::Node loadYamlString(const std::string& text, const std::string& label);

/// Parse one YAML value of any kind (a --set value) with the same strictness and limits.
YAML::Node loadYamlValue(const std::string& text, const std::string& label);

/// Deep merge: every key of `over` replaces or extends the one in `base` (mappings merged recursively).
YAML::Node mergeYaml(const YAML::Node& base, const YAML::Node& over);

/// The configuration layers of a command: `defaults` <- the file (if not "") <- the "key=value" overrides.
/// `label` receives what messages name: the file (or "<defaults>"), plus " (with --set overrides)" if any.
YAML::Node loadLayered(const YAML::Node& defaults, const std::string& file, const std::vector<std::string>& overrides,
                       std::string& label);

/// Emit as block-style YAML text.
std::string toYamlString(const YAML::Node& node);

}  // namespace centaur
