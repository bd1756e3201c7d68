#include "common/yaml_reader.hpp"

#include <fstream>
#include <sstream>

namespace centaur {

namespace {
std::string rangeText(double lo, double hi) {
  std::ostringstream os;
  os << "[" << lo << ", " << hi << "]";
  return os.str();
}
}  // namespace

YamlReader::YamlReader(const YAML::Node& node, std::string file, std::string prefix)
    : node_(node), file_(std::move(file)), prefix_(std::move(prefix)) {
  if (node_ && !node_.IsNull() && !node_.IsMap()) {
    throw InputError(file_, prefix_.empty() ? "<root>" : prefix_, "expected a mapping of key: value");
  }
}

void YamlReader::fail(const std::string& key, const std::string& message) const {
  throw InputError(file_, full(key), message);
}

bool YamlReader::has(const std::string& key) const { return node_ && node_.IsMap() && node_[key]; }

void YamlReader::get(const std::string& key, double& value, double lo, double hi) {
  if (!has(key)) return;
  used_.insert(key);
  double v = 0.0;
  try {
    v = node_[key].as<double>();
  } catch (const YAML::Exception&) {
    fail(key, "expected a number in " + rangeText(lo, hi));
  }
  if (!(v >= lo && v <= hi)) fail(key, "value " + node_[key].as<std::string>() + " outside the allowed range " + rangeText(lo, hi));
  value = v;
}

void YamlReader::get(const std::string& key, int& value, int lo, int hi) {
  if (!has(key)) return;
  used_.insert(key);
  int v = 0;
  try {
    v = node_[key].as<int>();
  } catch (const YAML::Exception&) {
    fail(key, "expected an integer in " + rangeText(lo, hi));
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
    if (!ok) fail(key, "value '" + v + "' is not one of: " + list);
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
    if (!(v >= lo && v <= hi)) fail(key, "element " + std::to_string(i) + " = " + n[i].as<std::string>() + " outside " + rangeText(lo, hi));
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
  for (const auto& kv : node_) {
    const std::string k = kv.first.as<std::string>();
    if (!used_.count(k)) unknown += (unknown.empty() ? "" : ", ") + full(k);
  }
  if (!unknown.empty()) throw InputError(file_ + ": unknown key(s): " + unknown + " (see the documented configuration)");
}

void applyOverride(YAML::Node& root, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw InputError("--set '" + assignment + "': expected key=value, e.g. --set cost.target_height=0.3");
  }
  const std::string path = assignment.substr(0, eq);
  const std::string text = assignment.substr(eq + 1);
  YAML::Node value;
  try {
    value = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError("--set '" + assignment + "': value is not valid YAML: " + e.what());
  }
  std::vector<std::string> keys;
  std::stringstream ss(path);
  for (std::string k; std::getline(ss, k, '.');) {
    if (k.empty()) throw InputError("--set '" + assignment + "': empty key segment");
    keys.push_back(k);
  }
  // yaml-cpp nodes are handles: walk by reassigning a chain of nodes.
  std::vector<YAML::Node> chain{root};
  for (std::size_t i = 0; i + 1 < keys.size(); ++i) {
    YAML::Node next = chain.back()[keys[i]];
    if (!next || next.IsNull()) {
      chain.back()[keys[i]] = YAML::Node(YAML::NodeType::Map);
      next = chain.back()[keys[i]];
    }
    if (!next.IsMap()) throw InputError("--set '" + assignment + "': '" + keys[i] + "' is not a mapping");
    chain.push_back(next);
  }
  chain.back()[keys.back()] = value;
}

YAML::Node loadYamlFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the file");
  try {
    YAML::Node n = YAML::Load(in);
    if (n.IsNull()) return YAML::Node(YAML::NodeType::Map);
    return n;
  } catch (const YAML::ParserException& e) {
    throw InputError(path + ": malformed YAML at line " + std::to_string(e.mark.line + 1) + ", column " +
                     std::to_string(e.mark.column + 1) + ": " + e.msg);
  }
}

YAML::Node loadYamlString(const std::string& text, const std::string& label) {
  try {
    YAML::Node n = YAML::Load(text);
    if (n.IsNull()) return YAML::Node(YAML::NodeType::Map);
    return n;
  } catch (const YAML::ParserException& e) {
    throw InputError(label + ": malformed YAML at line " + std::to_string(e.mark.line + 1) + ": " + e.msg);
  }
}

YAML::Node loadLayered(const YAML::Node& defaults, const std::string& file, const std::vector<std::string>& overrides,
                       std::string& label) {
  YAML::Node root = defaults;
  label = "<defaults>";
  if (!file.empty()) {
    root = mergeYaml(root, loadYamlFile(file));
    label = file;
  }
  for (const auto& o : overrides) applyOverride(root, o);
  if (!overrides.empty()) label += " (with --set overrides)";
  return root;
}

YAML::Node mergeYaml(const YAML::Node& base, const YAML::Node& over) {
  if (!over || over.IsNull()) return YAML::Clone(base);
  if (!base || !base.IsMap() || !over.IsMap()) return YAML::Clone(over);
  YAML::Node out = YAML::Clone(base);
  for (const auto& kv : over) {
    const std::string k = kv.first.as<std::string>();
    if (out[k] && out[k].IsMap() && kv.second.IsMap()) {
      out[k] = mergeYaml(out[k], kv.second);
    } else {
      out[k] = YAML::Clone(kv.second);
    }
  }
  return out;
}

std::string toYamlString(const YAML::Node& node) {
  YAML::Emitter e;
  e << node;
  return std::string(e.c_str()) + "\n";
}

}  // namespace centaur
