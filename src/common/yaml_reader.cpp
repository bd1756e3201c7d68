#include "common/yaml_reader.hpp"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/parser.h>

#include <sstream>
#include <unordered_map>
#include <unordered_set>

#include "common/excerpt.hpp"
#include "common/input_file.hpp"

namespace centaur {

namespace {
std::string rangeText(double lo, double hi) {
  std::ostringstream os;
  os << "[" << lo << ", " << hi << "]";
  return os.str();
}

/// "'<excerpt>'" of a scalar for messages.
std::string quoted(const YAML::Node& n) {
  if (n.IsScalar()) return "'" + excerpt(n.Scalar()) + "'";
  return n.IsSequence() ? "a list" : n.IsMap() ? "a mapping" : "null";
}

/// One streaming pass over the parser's events: the limits of YamlLimits and the strictness rules, before any
/// tree is built. Throws InputError naming `label` and the line.
class StrictChecker : public YAML::EventHandler {
 public:
  explicit StrictChecker(std::string label) : label_(std::move(label)) {}

  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    key(mark, nullptr, "an empty (null) key");
    leaf(mark, anchor);
  }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    key(mark, nullptr, "an alias (*name) as a key");
    const auto it = anchor_size_.find(anchor);
    if (it == anchor_size_.end()) fail(mark, "an alias refers to a mapping or list that contains it");
    count(mark, it->second);
    valueDone();
  }
  void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor, const std::string& value) override {
    key(mark, &value, "");
    leaf(mark, anchor);
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                       YAML::EmitterStyle::value) override {
    open(mark, anchor, false);
  }
  void OnSequenceEnd() override { close(); }
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor, YAML::EmitterStyle::value) override {
    open(mark, anchor, true);
  }
  void OnMapEnd() override { close(); }

 private:
  struct Frame {
    bool map;
    bool at_key;                          // a mapping expects a key next
    std::size_t first_node;               // nodes_ when the frame opened
    YAML::anchor_t anchor;
    std::unordered_set<std::string> keys;  // a mapping's keys so far
    std::unordered_map<std::string, int> lines;
  };

  [[noreturn]] void fail(const YAML::Mark& mark, const std::string& what) const {
    throw InputError(label_ + ": line " + std::to_string(mark.line + 1) + ", column " + std::to_string(mark.column + 1) +
                     ": " + what);
  }

  void count(const YAML::Mark& mark, std::size_t n) {
    nodes_ += n;
    if (nodes_ > YamlLimits::kMaxNodes) {
      fail(mark, "more than " + std::to_string(YamlLimits::kMaxNodes) +
                     " YAML nodes (keys, values and list items, aliases expanded): far more than any configuration "
                     "holds; refused");
    }
  }

  /// Called for every node: if the enclosing mapping expects a key, the node is that key. `scalar` is null for
  /// anything but a plain scalar; `kind` describes a forbidden key.
  void key(const YAML::Mark& mark, const std::string* scalar, const char* kind) {
    if (frames_.empty() || !frames_.back().map || !frames_.back().at_key) return;
    Frame& f = frames_.back();
    if (scalar == nullptr) fail(mark, std::string("a mapping key must be a plain name, found ") + kind);
    if (!f.keys.insert(*scalar).second) {
      fail(mark, "duplicate key '" + excerpt(*scalar) + "' (first at line " + std::to_string(f.lines[*scalar]) +
                     "): each key may appear once");
    }
    f.lines[*scalar] = mark.line + 1;
  }

  void leaf(const YAML::Mark& mark, YAML::anchor_t anchor) {
    count(mark, 1);
    if (anchor != YAML::NullAnchor) anchor_size_[anchor] = 1;
    valueDone();
  }

  /// A key or a value of the enclosing container is complete.
  void valueDone() {
    if (!frames_.empty() && frames_.back().map) frames_.back().at_key = !frames_.back().at_key;
  }

  void open(const YAML::Mark& mark, YAML::anchor_t anchor, bool map) {
    if (!frames_.empty() && frames_.back().map && frames_.back().at_key) {
      fail(mark, std::string("a mapping key must be a plain name, found ") + (map ? "a mapping" : "a list"));
    }
    count(mark, 1);
    if (static_cast<int>(frames_.size()) >= YamlLimits::kMaxDepth) {
      fail(mark, "nested deeper than " + std::to_string(YamlLimits::kMaxDepth) + " levels");
    }
    frames_.push_back(Frame{map, map, nodes_, anchor, {}, {}});
  }

  void close() {
    const Frame& f = frames_.back();
    if (f.anchor != YAML::NullAnchor) anchor_size_[f.anchor] = nodes_ - f.first_node + 1;
    frames_.pop_back();
    valueDone();
  }

  std::string label_;
  std::vector<Frame> frames_;
  std::size_t nodes_ = 0;
  std::unordered_map<YAML::anchor_t, std::size_t> anchor_size_;
};

std::string malformed(const std::string& label, const YAML::Exception& e) {
  return label + ": malformed YAML at line " + std::to_string(e.mark.line + 1) + ", column " +
         std::to_string(e.mark.column + 1) + ": " + excerpt(e.msg, 2 * kMaxExcerpt);
}

/// Strictly checked, then parsed; `mapping`: the root must be a mapping (null -> empty mapping).
YAML::Node parseStrict(const std::string& text, const std::string& label, bool mapping) {
  if (text.size() > YamlLimits::kMaxBytes) {
    throw InputError(label + ": " + std::to_string(text.size()) + " bytes of YAML, more than the limit of " +
                     std::to_string(YamlLimits::kMaxBytes));
  }
  YAML::Node n;
  try {
    std::istringstream in(text);
    YAML::Parser parser(in);
    StrictChecker checker(label);
    if (parser.HandleNextDocument(checker) && parser.HandleNextDocument(checker)) {
      throw InputError(label + ": holds more than one YAML document ('---'); give one");
    }
    n = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError(malformed(label, e));
  }
  if (!mapping) return n;
  if (!n || n.IsNull()) return YAML::Node(YAML::NodeType::Map);
  if (!n.IsMap()) {
    throw InputError(label, "<root>", "expected a mapping of key: value, found " +
                                          (n.IsScalar() ? "the scalar " + quoted(n) : std::string("a list")));
  }
  return n;
}
}  // namespace

YamlReader::YamlReader(const YAML::Node& node, std::string file, std::string prefix)
    : node_(node), file_(std::move(file)), prefix_(std::move(prefix)) {
  if (node_ && !node_.IsNull() && !node_.IsMap()) {
    throw InputError(file_, prefix_.empty() ? "<root>" : prefix_, "expected a mapping of key: value");
  }
}

void YamlReader::fail(const std::string& key, const std::string& message) const {
  throw InputError(file_, excerpt(full(key)), message);
}

bool YamlReader::has(const std::string& key) const { return node_ && node_.IsMap() && node_[key]; }

void YamlReader::get(const std::string& key, double& value, double lo, double hi) {
  if (!has(key)) return;
  used_.insert(key);
  double v = 0.0;
  try {
    v = node_[key].as<double>();
  } catch (const YAML::Exception&) {
    fail(key, "expected a number in " + rangeText(lo, hi) + ", found " + quoted(node_[key]));
  }
  if (!(v >= lo && v <= hi)) fail(key, "value " + quoted(node_[key]) + " outside the allowed range " + rangeText(lo, hi));
  value = v;
}

void YamlReader::get(const std::string& key, int& value, int lo, int hi) {
  if (!has(key)) return;
  used_.insert(key);
  int v = 0;
  try {
    v = node_[key].as<int>();
  } catch (const YAML::Exception&) {
    fail(key, "expected an integer in " + rangeText(lo, hi) + ", found " + quoted(node_[key]));
  }
  if (v < lo || v > hi) fail(key, "value " + std::to_string(v) + " outside the allowed range " + rangeText(lo, hi));
  value = v;
}

void YamlReader::get(const std::string& key, bool& value) {
  if (!has(key)) return;
  used_.insert(key);
  try {
    value = node_[key].as<bool>();
  } catch (const YAML::Exception&) {
    fail(key, "expected true or false");
  }
}

void YamlReader::get(const std::string& key, std::string& value, const std::vector<std::string>& allowed) {
  if (!has(key)) return;
  used_.insert(key);
  std::string v;
  try {
    v = node_[key].as<std::string>();
  } catch (const YAML::Exception&) {
    fail(key, "expected a string");
  }
  if (!allowed.empty()) {
    bool ok = false;
    std::string list;
    for (const auto& a : allowed) {
      ok = ok || a == v;
      list += (list.empty() ? "" : ", ") + a;
    }
    if (!ok) fail(key, "value '" + excerpt(v) + "' is not one of: " + list);
  }
  value = v;
}

void YamlReader::get(const std::string& key, Eigen::Ref<Eigen::VectorXd> value, double lo, double hi) {
  if (!has(key)) return;
  used_.insert(key);
  const YAML::Node n = node_[key];
  const std::string expect = "expected a list of " + std::to_string(value.size()) + " numbers, each in " + rangeText(lo, hi);
  if (!n.IsSequence() || static_cast<Eigen::Index>(n.size()) != value.size()) fail(key, expect);
  for (std::size_t i = 0; i < n.size(); ++i) {
    double v = 0.0;
    try {
      v = n[i].as<double>();
    } catch (const YAML::Exception&) {
      fail(key, expect);
    }
    if (!(v >= lo && v <= hi)) fail(key, "element " + std::to_string(i) + " = " + quoted(n[i]) + " outside " + rangeText(lo, hi));
    value[static_cast<Eigen::Index>(i)] = v;
  }
}

void YamlReader::getInterval(const std::string& key, Eigen::Vector2d& value, double lo, double hi) {
  Eigen::VectorXd x = value;
  get(key, x, lo, hi);
  if (x[0] >= x[1]) fail(key, "expected [lower, upper] with lower < upper");
  value = x;
}

void YamlReader::get(const std::string& key, std::vector<double>& value, double lo, double hi) {
  if (!has(key)) return;
  used_.insert(key);
  const YAML::Node n = node_[key];
  if (!n.IsSequence()) fail(key, "expected a list of numbers, each in " + rangeText(lo, hi));
  std::vector<double> out;
  for (std::size_t i = 0; i < n.size(); ++i) {
    double v = 0.0;
    try {
      v = n[i].as<double>();
    } catch (const YAML::Exception&) {
      fail(key, "expected a list of numbers, each in " + rangeText(lo, hi));
    }
    if (!(v >= lo && v <= hi)) fail(key, "element " + std::to_string(i) + " outside " + rangeText(lo, hi));
    out.push_back(v);
  }
  value = out;
}

void YamlReader::getPoints(const std::string& key, Eigen::Vector3d* points, int count, double lo, double hi,
                           const std::string& what) {
  if (!has(key)) return;
  used_.insert(key);
  const YAML::Node n = node_[key];
  const std::string expect =
      "expected " + std::to_string(count) + " " + what + " [x, y, z], each coordinate in " + rangeText(lo, hi);
  if (!n.IsSequence() || static_cast<int>(n.size()) != count) fail(key, expect);
  for (int i = 0; i < count; ++i) {
    if (!n[i].IsSequence() || n[i].size() != 3) fail(key, expect);
    for (int a = 0; a < 3; ++a) {
      double v = 0.0;
      try {
        v = n[i][a].as<double>();
      } catch (const YAML::Exception&) {
        fail(key, expect);
      }
      if (!(v >= lo && v <= hi)) fail(key, "point " + std::to_string(i) + " outside " + rangeText(lo, hi));
      points[i][a] = v;
    }
  }
}

YamlReader YamlReader::child(const std::string& key) {
  if (has(key)) used_.insert(key);
  return YamlReader(has(key) ? node_[key] : YAML::Node(), file_, full(key));
}

YAML::Node YamlReader::raw(const std::string& key) {
  if (!has(key)) return YAML::Node();
  used_.insert(key);
  return node_[key];
}

void YamlReader::finish() const {
  if (!node_ || !node_.IsMap()) return;
  std::string unknown;
  std::size_t count = 0;
  for (const auto& kv : node_) {
    const std::string k = kv.first.IsScalar() ? kv.first.Scalar() : std::string("<complex key>");
    if (used_.count(k)) continue;
    if (++count <= YamlLimits::kMaxUnknownKeysNamed) unknown += (unknown.empty() ? "" : ", ") + excerpt(full(k));
  }
  if (count == 0) return;
  if (count > YamlLimits::kMaxUnknownKeysNamed) {
    unknown += " and " + std::to_string(count - YamlLimits::kMaxUnknownKeysNamed) + " more";
  }
  throw InputError(file_ + ": unknown key(s): " + unknown + " (see the documented configuration)");
}

void applyOverride(YAML::Node& root, const std::string& assignment) {
  const std::string shown = "--set '" + excerpt(assignment) + "'";
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw InputError(shown + ": expected key=value, e.g. --set cost.target_height=0.3");
  }
  const std::string path = assignment.substr(0, eq);
  const YAML::Node value = loadYamlValue(assignment.substr(eq + 1), shown + ": value");
  std::vector<std::string> keys;
  std::stringstream ss(path);
  for (std::string k; std::getline(ss, k, '.');) {
    if (k.empty()) throw InputError(shown + ": empty key segment");
    if (static_cast<int>(keys.size()) >= YamlLimits::kMaxDepth) {
      throw InputError(shown + ": more than " + std::to_string(YamlLimits::kMaxDepth) + " key segments");
    }
    keys.push_back(k);
  }
  if (!path.empty() && path.back() == '.') throw InputError(shown + ": empty key segment");
  // yaml-cpp nodes are handles: walk by reassigning a chain of nodes.
  std::vector<YAML::Node> chain{root};
  for (std::size_t i = 0; i + 1 < keys.size(); ++i) {
    YAML::Node next = chain.back()[keys[i]];
    if (!next || next.IsNull()) {
      chain.back()[keys[i]] = YAML::Node(YAML::NodeType::Map);
      next = chain.back()[keys[i]];
    }
    if (!next.IsMap()) throw InputError(shown + ": '" + excerpt(keys[i]) + "' is not a mapping");
    chain.push_back(next);
  }
  chain.back()[keys.back()] = value;
}

YAML::Node loadYamlFile(const std::string& path) {
  const std::string text = readSmallFile(path, YamlLimits::kMaxBytes, "a YAML configuration");
  return parseStrict(text, excerpt(path, 4 * kMaxExcerpt), true);
}

YAML::Node loadYamlString(const std::string& text, const std::string& label) { return parseStrict(text, label, true); }

YAML::Node loadYamlValue(const std::string& text, const std::string& label) { return parseStrict(text, label, false); }

YAML::Node loadLayered(const YAML::Node& defaults, const std::string& file, const std::vector<std::string>& overrides,
                       std::string& label) {
  YAML::Node root = defaults;
  label = "<defaults>";
  if (!file.empty()) {
    root = mergeYaml(root, loadYamlFile(file));
    label = excerpt(file, 4 * kMaxExcerpt);
  }
  for (const auto& o : overrides) applyOverride(root, o);
  if (!overrides.empty()) label += " (with --set overrides)";
  return root;
}

YAML::Node mergeYaml(const YAML::Node& base, const YAML::Node& over) {
  if (!over || over.IsNull()) return YAML::Clone(base);
  if (!base || !base.IsMap() || !over.IsMap()) return YAML::Clone(over);
  // Linear in the number of keys: one hash lookup per key instead of yaml-cpp's linear search per key.
  std::unordered_map<std::string, YAML::Node> over_by_key;
  for (const auto& kv : over) over_by_key.emplace(kv.first.Scalar(), kv.second);
  std::unordered_set<std::string> base_keys;
  YAML::Node out(YAML::NodeType::Map);
  out.SetStyle(base.Style());  // the effective configuration is written in the style of the defaults
  for (const auto& kv : base) {
    const std::string& k = kv.first.Scalar();
    base_keys.insert(k);
    const auto it = over_by_key.find(k);
    if (it == over_by_key.end()) {
      out.force_insert(k, YAML::Clone(kv.second));
    } else if (kv.second.IsMap() && it->second.IsMap()) {
      out.force_insert(k, mergeYaml(kv.second, it->second));
    } else {
      out.force_insert(k, YAML::Clone(it->second));
    }
  }
  for (const auto& kv : over) {
    if (!base_keys.count(kv.first.Scalar())) out.force_insert(kv.first.Scalar(), YAML::Clone(kv.second));
  }
  return out;
}

std::string toYamlString(const YAML::Node& node) {
  YAML::Emitter e;
  e << node;
  return std::string(e.c_str()) + "\n";
}

}  // namespace centaur
