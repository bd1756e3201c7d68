// ctest-labels: unit
// Strict YAML loading (common/yaml_reader.hpp): one document, a mapping at the root, unique plain keys, the size
// limits of YamlLimits refused in one streaming pass, bounded excerpts in messages, the first unknown keys named.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "common/excerpt.hpp"
#include "common/yaml_reader.hpp"
#include "support/temp_dir.hpp"

using centaur::InputError;
using centaur::YamlLimits;

namespace {

/// The InputError message of loading `text`, "" if it loads.
std::string refusal(const std::string& text) {
  try {
    centaur::loadYamlString(text, "cfg.yaml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(YamlStrict, DuplicateKeysAreRefusedWithBothLines) {
  const std::string msg = refusal("a: 1\nb: {x: 1}\na: 2\n");
  EXPECT_NE(msg.find("duplicate key 'a'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("line 3"), std::string::npos) << msg;
  EXPECT_NE(msg.find("first at line 1"), std::string::npos) << msg;
  EXPECT_NE(refusal("b: {x: 1, x: 2}\n").find("duplicate key 'x'"), std::string::npos);
  EXPECT_EQ(refusal("a: {x: 1}\nb: {x: 2}\n"), "") << "the same key in two mappings is fine";
}

TEST(YamlStrict, SeveralDocumentsAreRefused) {
  EXPECT_NE(refusal("a: 1\n---\nb: 2\n").find("more than one YAML document"), std::string::npos);
  EXPECT_EQ(refusal("---\na: 1\n"), "") << "one document with a start marker is fine";
}

TEST(YamlStrict, TheRootMustBeAMapping) {
  EXPECT_NE(refusal("just a scalar\n").find("expected a mapping"), std::string::npos);
  EXPECT_NE(refusal("- 1\n- 2\n").find("expected a mapping"), std::string::npos);
  EXPECT_TRUE(centaur::loadYamlString("", "cfg.yaml").IsMap()) << "an empty file is an empty mapping";
  EXPECT_TRUE(centaur::loadYamlValue("3.5", "--set").IsScalar()) << "a --set value may be anything";
}

TEST(YamlStrict, KeysMustBePlainNames) {
  EXPECT_NE(refusal("? [a, b]\n: 1\n").find("plain name"), std::string::npos);
  EXPECT_NE(refusal("? {a: 1}\n: 1\n").find("plain name"), std::string::npos);
  EXPECT_NE(refusal("x: &k key\n*k : 1\n").find("alias"), std::string::npos);
  EXPECT_NE(refusal("~: 1\n").find("null"), std::string::npos);
}

TEST(YamlStrict, AliasesCountExpandedSoABillionLaughsIsRefused) {
  std::string text = "l0: &l0 [x, x, x, x, x, x, x, x, x, x]\n";
  for (int i = 1; i < 10; ++i) {
    text += "l" + std::to_string(i) + ": &l" + std::to_string(i) + " [";
    for (int k = 0; k < 10; ++k) text += std::string(k ? ", " : "") + "*l" + std::to_string(i - 1);
    text += "]\n";
  }
  const std::string msg = refusal(text);  // 10^10 nodes once expanded
  EXPECT_NE(msg.find("more than " + std::to_string(YamlLimits::kMaxNodes)), std::string::npos) << msg;
  EXPECT_EQ(refusal("a: &x {k: 1}\nb: *x\n"), "") << "a small alias is fine";
}

TEST(YamlStrict, ManyKeysAreRefusedByTheNodeLimitNotByQuadraticWork) {
  // 100 000 unknown keys (under 1 MB) are refused by the node limit, twice as many by the byte limit.
  std::string text;
  for (int i = 0; i < 100000; ++i) text += "k" + std::to_string(i) + ": 1\n";
  ASSERT_LT(text.size(), YamlLimits::kMaxBytes);
  const std::string msg = refusal(text);
  EXPECT_NE(msg.find("nodes"), std::string::npos) << msg.substr(0, 300);
  EXPECT_LT(msg.size(), 400u);
  std::string big = text + text;
  EXPECT_NE(refusal(big).find("more than the limit"), std::string::npos);
}

TEST(YamlStrict, DeepNestingIsRefused) {
  const std::string text = "a: " + std::string(200, '[') + std::string(200, ']') + "\n";
  EXPECT_NE(refusal(text).find("nested deeper"), std::string::npos);
  YAML::Node root(YAML::NodeType::Map);
  std::string key = "a";
  for (int i = 0; i < 100; ++i) key += ".a";
  EXPECT_THROW(centaur::applyOverride(root, key + "=1"), InputError) << "--set with more than 64 segments";
}

TEST(YamlStrict, MessagesQuoteBoundedExcerpts) {
  const std::string huge(500000, '9');
  YAML::Node n = centaur::loadYamlString("mass: " + huge + "\n" + std::string(300, 'k') + ": 1\n", "cfg.yaml");
  centaur::YamlReader r(n, "cfg.yaml");
  double mass = 0.0;
  try {
    r.get("mass", mass, 0.0, 10.0);
    FAIL();
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_LT(msg.size(), 400u) << "a 500 kB value is quoted as an excerpt";
    EXPECT_NE(msg.find("(500000 bytes)"), std::string::npos) << msg;
  }
  try {
    r.finish();
    FAIL();
  } catch (const InputError& e) {
    EXPECT_LT(std::string(e.what()).size(), 400u);
  }
  EXPECT_EQ(centaur::excerpt("a\nb\x1b[31m"), "a\\nb\\x1b[31m") << "control characters are escaped";
}

TEST(YamlStrict, TheFirstUnknownKeysAreNamedThenCounted) {
  YAML::Node n = centaur::loadYamlString("a: 1\nb: 2\nc: 3\nd: 4\ne: 5\nf: 6\ng: 7\n", "cfg.yaml");
  centaur::YamlReader r(n, "cfg.yaml");
  try {
    r.finish();
    FAIL();
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("a, b, c, d, e and 2 more"), std::string::npos) << msg;
    EXPECT_EQ(msg.find("f,"), std::string::npos) << msg;
  }
}

TEST(YamlStrict, NonFiniteNumbersAreOutsideEveryRange) {
  for (const char* v : {".nan", ".inf", "-.inf", "nan"}) {
    YAML::Node n = centaur::loadYamlString(std::string("x: ") + v + "\n", "cfg.yaml");
    centaur::YamlReader r(n, "cfg.yaml");
    double x = 1.0;
    EXPECT_THROW(r.get("x", x, -1e300, 1e300), InputError) << v;
    EXPECT_EQ(x, 1.0);
  }
}

TEST(YamlStrict, FilesMustBeRegularAndSmall) {
  centaur_test::TempDir dir;
  EXPECT_THROW(centaur::loadYamlFile(dir.path().string()), InputError) << "a directory";
  EXPECT_THROW(centaur::loadYamlFile("/dev/zero"), InputError) << "a device";
  EXPECT_THROW(centaur::loadYamlFile(dir.file("missing.yaml")), InputError);
  std::ofstream(dir.file("big.yaml")) << std::string(YamlLimits::kMaxBytes + 1, '#');
  try {
    centaur::loadYamlFile(dir.file("big.yaml"));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("limit"), std::string::npos) << e.what();
  }
}

TEST(YamlStrict, MergeKeepsOrderAndReplacesLeaves) {
  const YAML::Node base = centaur::loadYamlString("a: 1\nb: {x: 1, y: 2}\nc: 3\n", "base");
  const YAML::Node over = centaur::loadYamlString("b: {y: 5, z: 6}\nd: 4\na: 0\n", "over");
  const YAML::Node m = centaur::mergeYaml(base, over);
  // The base's order, then the new keys; a merged mapping keeps the base's style (here flow), so the effective
  // configuration reads the same whether or not a file overrides the defaults.
  EXPECT_EQ(centaur::toYamlString(m), "a: 0\nb: {x: 1, y: 5, z: 6}\nc: 3\nd: 4\n");
}
