#include <gtest/gtest.h>

#include "common/yaml_reader.hpp"

using centaur::InputError;
using centaur::YamlReader;

TEST(YamlReader, ReadsValuesAndKeepsDefaults) {
  YAML::Node n = YAML::Load("a: 1.5\nb: 3\nc: {d: true}\n");
  YamlReader r(n, "cfg.yaml");
  double a = 0.0, missing = 7.0;
  int b = 0;
  bool d = false;
  r.get("a", a, 0.0, 2.0);
  r.get("b", b, 0, 10);
  r.get("zzz", missing, 0.0, 10.0);
  auto c = r.child("c");
  c.get("d", d);
  c.finish();
  r.finish();
  EXPECT_DOUBLE_EQ(a, 1.5);
  EXPECT_EQ(b, 3);
  EXPECT_TRUE(d);
  EXPECT_DOUBLE_EQ(missing, 7.0);
}

TEST(YamlReader, OutOfRangeNamesFileKeyAndRange) {
  YAML::Node n = YAML::Load("model: {mass: -2}\n");
  YamlReader r(n, "cfg.yaml");
  auto m = r.child("model");
  double mass = 1.0;
  try {
    m.get("mass", mass, 1e-3, 1e4);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("cfg.yaml"), std::string::npos) << msg;
    EXPECT_NE(msg.find("model.mass"), std::string::npos) << msg;
    EXPECT_NE(msg.find("[0.001, 10000]"), std::string::npos) << msg;
  }
}

TEST(YamlReader, UnknownKeyIsAnError) {
  YAML::Node n = YAML::Load("a: 1\ntypo: 2\n");
  YamlReader r(n, "cfg.yaml");
  double a = 0;
  r.get("a", a, 0, 10);
  try {
    r.finish();
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("typo"), std::string::npos);
  }
}

TEST(YamlReader, OverrideCreatesNestedKeysAndParsesValues) {
  YAML::Node n = YAML::Load("x: {y: 1}\n");
  centaur::applyOverride(n, "x.y=2.5");
  centaur::applyOverride(n, "p.q.r=[1, 2]");
  EXPECT_DOUBLE_EQ(n["x"]["y"].as<double>(), 2.5);
  EXPECT_EQ(n["p"]["q"]["r"].size(), 2u);
  EXPECT_THROW(centaur::applyOverride(n, "novalue"), InputError);
}

TEST(YamlReader, MalformedYamlNamesLine) {
  try {
    centaur::loadYamlString("a: [1, 2\nb: 3\n", "bad.yaml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.yaml"), std::string::npos);
  }
}
