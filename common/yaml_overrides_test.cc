#include "common/yaml_overrides.h"

#include <gtest/gtest.h>

#include "common/error.h"
#include "common/testing/error_of.h"

namespace depot {
namespace {

TEST(YamlOverrides, ParsesKeyAndValue) {
  const YamlOverride o = parse_yaml_override("sensor.rgb_noise=4.5", "--set");
  EXPECT_EQ(o.key, "sensor.rgb_noise");
  EXPECT_EQ(o.value, "4.5");
  EXPECT_EQ(parse_yaml_override("a=b=c", "--set").value, "b=c");
}

TEST(YamlOverrides, RejectsMalformedText) {
  EXPECT_THROW(parse_yaml_override("noequals", "--set"), Error);
  EXPECT_THROW(parse_yaml_override("=3", "--set"), Error);
  EXPECT_THROW(parse_yaml_override("a..b=3", "--set"), Error);
  EXPECT_THROW(parse_yaml_override("a=", "--set"), Error);
}

TEST(YamlOverrides, SetsNestedKeysKeepingSiblingsAndTypes) {
  YAML::Node root = YAML::Load("sensor: {rgb_noise: 2, ideal: false}\nframes: 10\n");
  apply_yaml_override(root, {"sensor.rgb_noise", "4.5"}, "--set");
  apply_yaml_override(root, {"camera.width", "320"}, "--set");
  apply_yaml_override(root, {"frames", "[1, 2]"}, "--set");
  EXPECT_DOUBLE_EQ(root["sensor"]["rgb_noise"].as<double>(), 4.5);
  EXPECT_FALSE(root["sensor"]["ideal"].as<bool>());
  EXPECT_EQ(root["camera"]["width"].as<int>(), 320);
  ASSERT_TRUE(root["frames"].IsSequence());
  EXPECT_EQ(root["frames"].size(), 2u);
}

TEST(YamlOverrides, RefusesToDescendIntoAScalar) {
  YAML::Node root = YAML::Load("frames: 10\n");
  EXPECT_NE(error_of([&] {
              apply_yaml_override(root, {"frames.x", "1"}, "--set");
            }).find("'frames' is not a map"),
            std::string::npos);
}

TEST(YamlOverrides, BuildsANodeFromAList) {
  YAML::Node node = overrides_to_node({{"miss_rate", "0.2"}, {"latency_frames", "2"}}, "--set");
  EXPECT_DOUBLE_EQ(node["miss_rate"].as<double>(), 0.2);
  EXPECT_EQ(node["latency_frames"].as<int>(), 2);
}

}  // namespace
}  // namespace depot
