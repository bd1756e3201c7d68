#include "sweep/yaml_values.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>

#include "common/error.hpp"
#include "common/number_text.hpp"

namespace centaur::sweep {

bool scalarNumber(const YAML::Node& node, double& x) {
  if (!node.IsScalar()) return false;
  const std::string& s = node.Scalar();
  if (s.empty() || std::isspace(static_cast<unsigned char>(s.front()))) return false;
  char* end = nullptr;
  x = std::strtod(s.c_str(), &end);
  return end != nullptr && *end == '\0' && std::isfinite(x);
}

std::string valueText(const YAML::Node& node, const std::string& file, const std::string& key) {
  double x = 0.0;
  if (scalarNumber(node, x)) return exactNumber(x);
  if (node.IsScalar()) {
    YAML::Emitter e;
    e << node.Scalar();
    return e.c_str();
  }
  if (node.IsSequence()) {
    std::string s = "[";
    for (std::size_t i = 0; i < node.size(); ++i) s += (i ? ", " : "") + valueText(node[i], file, key);
    return s + "]";
  }
  if (node.IsNull()) return "null";
  throw InputError(file, key, "expected a value (a number, a string or a list), not a mapping; give the dotted key of "
                              "each leaf instead, e.g. sensors.noise.q: 0.001");
}

std::vector<double> numbers(const YAML::Node& node, int size, bool broadcast, const std::string& file,
                            const std::string& key) {
  double x = 0.0;
  const std::string expect = size == 1 ? "a number" : "a list of " + std::to_string(size) + " numbers" +
                                                        (broadcast ? " (or one number for all)" : "");
  if (scalarNumber(node, x)) {
    if (size != 1 && !broadcast) throw InputError(file, key, "expected " + expect);
    return std::vector<double>(static_cast<std::size_t>(size), x);
  }
  if (!node.IsSequence() || static_cast<int>(node.size()) != size || size == 1) {
    throw InputError(file, key, "expected " + expect);
  }
  std::vector<double> out;
  for (std::size_t i = 0; i < node.size(); ++i) {
    if (!scalarNumber(node[i], x)) throw InputError(file, key, "expected " + expect);
    out.push_back(x);
  }
  return out;
}

std::string numbersText(const std::vector<double>& v) {
  if (v.size() == 1) return exactNumber(v.front());
  std::string s = "[";
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + exactNumber(v[i]);
  return s + "]";
}

void checkKeyName(const std::string& name, const std::string& file, const std::string& key) {
  bool ok = !name.empty() && (std::isalpha(static_cast<unsigned char>(name.front())) || name.front() == '_');
  for (char c : name) ok = ok && (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '-');
  ok = ok && name.back() != '.' && name.find("..") == std::string::npos;
  if (!ok) throw InputError(file, key, "'" + name + "' is not a dotted key (letters, digits, '_', '-', '.')");
}

}  // namespace centaur::sweep
