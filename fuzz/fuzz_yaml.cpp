// Fuzz target: the strict YAML reader (common/yaml_reader.hpp): loading (limits, duplicates, documents, keys),
// --set overrides, the merge of layers, and every typed get() with its range checks and excerpts.
#include <Eigen/Core>

#include "common/yaml_reader.hpp"
#include "fuzz_support.hpp"

namespace {

/// Reads every key of the mapping once, with a getter chosen by the key's node (and a byte of the input), then
/// descends into child mappings; finish() names what was not read.
void readEverything(centaur::YamlReader r, const YAML::Node& node, unsigned salt, int depth) {
  if (!node.IsMap()) return;
  int count = 0;
  for (const auto& kv : node) {
    if (++count > 32) break;
    const std::string key = kv.first.Scalar();
    const YAML::Node& v = kv.second;
    const unsigned pick = (salt + static_cast<unsigned>(key.size()) * 7u + static_cast<unsigned>(count)) % 8u;
    centaur_fuzz::expectOnlyInputErrors([&] {
      if (v.IsMap()) {
        if (depth < 4) readEverything(r.child(key), v, salt * 31u + 1u, depth + 1);
        return;
      }
      double d = 0.0;
      int i = 0;
      bool b = false;
      std::string s;
      Eigen::VectorXd v3(3);
      Eigen::Vector2d iv(0.0, 1.0);
      std::vector<double> vd;
      Eigen::Vector3d pts[4];
      switch (pick) {
        case 0: r.get(key, d, -1e6, 1e6); break;
        case 1: r.get(key, i, -1000, 1000); break;
        case 2: r.get(key, b); break;
        case 3: r.get(key, s, {"x", "y"}); break;
        case 4: r.get(key, v3, -10.0, 10.0); break;
        case 5: r.getInterval(key, iv, -10.0, 10.0); break;
        case 6: r.get(key, vd, -10.0, 10.0); break;
        default: r.getPoints(key, pts, 4, -2.0, 2.0, "points"); break;
      }
    });
  }
  centaur_fuzz::expectOnlyInputErrors([&] { r.finish(); });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // Part 1: a configuration file; further NUL-separated parts: --set overrides.
  const std::vector<std::string> parts = centaur_fuzz::splitNul(data, size, 5);
  centaur_fuzz::expectOnlyInputErrors([&] {
    const YAML::Node defaults = centaur::loadYamlString("a: 1\nb: {x: 2}\nlist: [1, 2, 3]\n", "<defaults>");
    YAML::Node root = centaur::mergeYaml(defaults, centaur::loadYamlString(parts[0], "<fuzz>"));
    for (std::size_t i = 1; i < parts.size(); ++i) centaur::applyOverride(root, parts[i]);
    readEverything(centaur::YamlReader(root, "<fuzz>"), root, size > 0 ? data[0] : 0u, 0);
    centaur::toYamlString(root);
  });
  return 0;
}
