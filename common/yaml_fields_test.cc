#include "common/yaml_fields.h"

#include <gtest/gtest.h>

#include "common/testing/error_of.h"

namespace depot {
namespace {

YAML::Node parse(const std::string& text) {
  return YAML::Load(text);
}

TEST(YamlFields, AnAbsentMapOrKeyTakesTheFallback) {
  YAML::Node root = parse("a: {x: 1}\n");
  // root["b"] on a non-const node: absent, as config readers meet a missing
  // section.
  const YamlFields missing(root["b"], "f.yaml", "b");
  EXPECT_FALSE(missing.has("x"));
  EXPECT_EQ(missing.number<int>("x", 7, 0, 10), 7);
  EXPECT_TRUE(missing.flag("on", true));
  EXPECT_EQ(missing.str("name", "n"), "n");
  const YamlFields a(root["a"], "f.yaml", "a");
  EXPECT_EQ(a.number<int>("x", 7, 0, 10), 1);
  EXPECT_EQ(a.number("y", 0.5, 0, 1), 0.5);
}

TEST(YamlFields, WrongValuesAreOneErrorAtTheirLine) {
  const YAML::Node root = parse("name: x\ncam:\n  w: 10.5\n  on: maybe\n  r: 2\n  p: [1]\n");
  const YamlFields cam(root["cam"], "f.yaml", "cam");
  EXPECT_EQ(error_of([&] { cam.number<int>("w", 1, 0, 100); }), "f.yaml:3: bad value for 'w'");
  EXPECT_EQ(error_of([&] { cam.flag("on", false); }),
            "f.yaml:4: bad value for 'on' (true or false)");
  EXPECT_EQ(error_of([&] { cam.number("r", 0.5, 0, 1.5); }),
            "f.yaml:5: 'r' = 2 is out of range [0, 1.5]");
  EXPECT_EQ(error_of([&] { cam.vec2("p", {0, 0}); }), "f.yaml:6: 'p' must be [x, y]");
  EXPECT_EQ(error_of([&] { YamlFields(root["name"], "f.yaml", "name"); }),
            "f.yaml:1: name must be a map");
  EXPECT_EQ(error_of([&] {
              cam.allow_only({"w", "on", "r"});
            }),
            "f.yaml:6: unknown key 'p' (expected one of: w, on, r)");
}

TEST(YamlFields, AFallbackOutOfRangeIsPlacedAtTheMap) {
  const YAML::Node root = parse("name: x\ncam: {w: 1}\n");
  const YamlFields cam(root["cam"], "f.yaml", "cam");
  EXPECT_EQ(error_of([&] { cam.number("h", -1.0, 0, 1); }),
            "f.yaml:2: 'h' = -1 is out of range [0, 1]");
}

TEST(YamlFields, TheFallbackDoesNotChooseTheType) {
  // A double unless named: 2.5 read with an int fallback stays 2.5.
  const YAML::Node root = parse("v: 2.5\n");
  const YamlFields f(root, "f.yaml", "top");
  const int fallback = 1;
  EXPECT_EQ(f.number("v", fallback, 0, 10), 2.5);
  EXPECT_EQ(error_of([&] { f.number<int>("v", fallback, 0, 10); }), "f.yaml:1: bad value for 'v'");
  EXPECT_EQ(error_of([&] { f.number("v", 0.0, 0, 1e-6); }),
            "f.yaml:1: 'v' = 2.5 is out of range [0, 1e-06]");
}

TEST(YamlFields, AnOverriddenValueIsPlacedAtItsOption) {
  YAML::Node root = parse("sensor: {exposure: 0.01}\n");
  YAML::Node value = YAML::Load("-1");
  root["sensor"]["exposure"] = value;
  const YamlSource source{"s.yaml", {{root["sensor"]["exposure"], "--set sensor.exposure=-1"}}};
  const YamlFields sensor(root["sensor"], source, "sensor");
  EXPECT_EQ(error_of([&] { sensor.number("exposure", 0.0, 0, 0.5); }),
            "--set sensor.exposure=-1: 'exposure' = -1 is out of range [0, 0.5]");
}

TEST(YamlFields, AValueFoundByWalkingAMapIsReadTheSameWay) {
  const YAML::Node root = parse("rates:\n  dog: 0.5\n  cat: lots\n");
  const YamlSource source{"r.yaml", {}};
  double sum = 0;
  std::string error;
  for (const auto& kv : root["rates"]) {
    const std::string cls = yaml_value<std::string>(kv.first, "class", source);
    error = error_of([&] { sum += yaml_value<double>(kv.second, "rates: " + cls, source); });
  }
  EXPECT_EQ(sum, 0.5);
  EXPECT_EQ(error, "r.yaml:3: bad value for 'rates: cat'");
}

}  // namespace
}  // namespace depot
