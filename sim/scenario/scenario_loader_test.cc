// The scenario loader's command-line overrides (the sweep's parameters).
#include "sim/scenario/scenario_loader.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/error.h"
#include "common/testing/error_of.h"

namespace depot::sim {
namespace {

const std::string kWalking = std::string(DEPOT_SOURCE_DIR) + "/scenarios/depot_walking_xyz.yaml";

size_t living_actors(const Scenario& s) {
  size_t n = 0;
  for (const auto& a : s.actors) n += is_living_actor(a.type);
  return n;
}

TEST(ScenarioOverrides, ChangeTheKeysTheyName) {
  const Scenario plain = load_scenario(kWalking);
  const Scenario changed = load_scenario(
      kWalking, {{"sensor.rgb_noise", "4.5"}, {"dynamic_load", "2"}, {"frames", "40"}});
  EXPECT_DOUBLE_EQ(changed.sensor.rgb_noise, 4.5);
  EXPECT_DOUBLE_EQ(changed.sensor.disparity_noise, plain.sensor.disparity_noise);
  EXPECT_EQ(changed.frames, 40);
  EXPECT_DOUBLE_EQ(changed.dynamic_load, 2.0);
  EXPECT_EQ(living_actors(changed), 2 * living_actors(plain));
  EXPECT_EQ(load_scenario(kWalking, {{"dynamic_load", "0"}}).actors.size() + living_actors(plain),
            plain.actors.size());
}

TEST(ScenarioOverrides, AreValidatedLikeTheFile) {
  EXPECT_NE(error_of([] {
              load_scenario(kWalking, {{"sensor.bogus", "1"}});
            }).find("bogus"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              load_scenario(kWalking, {{"dynamic_load", "9"}});
            }).find("dynamic_load"),
            std::string::npos);
  EXPECT_NE(error_of([] { load_scenario(kWalking, {{"sensor.rgb_noise", "loud"}}); }), "");
}

TEST(ScenarioActorsStyle, DefaultsToMeshAndTakesPrimitive) {
  EXPECT_EQ(load_scenario(kWalking).actors_style, "mesh");
  EXPECT_EQ(load_scenario(kWalking, {{"actors_style", "primitive"}}).actors_style, "primitive");
  const std::string error = error_of([] { load_scenario(kWalking, {{"actors_style", "clay"}}); });
  // The option is to blame, not a line of the file it changes.
  EXPECT_NE(error.find("depot_walking_xyz.yaml: --set actors_style=clay: unknown actors_style "
                       "'clay' (expected primitive or mesh)"),
            std::string::npos)
      << error;
  EXPECT_THAT(error, ::testing::Not(::testing::HasSubstr(".yaml:1"))) << error;
  const std::string nested = error_of([] {
    load_scenario(kWalking, {{"sensor.rgb_noise", "loud"}});
  });
  EXPECT_THAT(nested, ::testing::HasSubstr("--set sensor.rgb_noise=loud")) << nested;
}

TEST(ScenarioPropsStyle, DefaultsToMeshAndTakesPrimitive) {
  EXPECT_EQ(load_scenario(kWalking).props_style, "mesh");
  const Scenario primitive = load_scenario(kWalking, {{"props_style", "primitive"}});
  EXPECT_EQ(primitive.props_style, "primitive");
  EXPECT_EQ(primitive.actors_style, "mesh") << "props_style leaves the actors alone";
  EXPECT_EQ(load_scenario(kWalking, {{"actors_style", "primitive"}}).props_style, "mesh");
  const std::string error = error_of([] { load_scenario(kWalking, {{"props_style", "wood"}}); });
  EXPECT_THAT(error, ::testing::HasSubstr("depot_walking_xyz.yaml")) << error;
  EXPECT_NE(error.find("unknown props_style 'wood' (expected primitive or mesh)"),
            std::string::npos)
      << error;
}

TEST(ScenarioStyle, SetsActorsAndPropsWhichMayOverrideIt) {
  const Scenario all = load_scenario(kWalking, {{"style", "mesh"}});
  EXPECT_EQ(all.actors_style, "mesh");
  EXPECT_EQ(all.props_style, "mesh");
  const Scenario people_only =
      load_scenario(kWalking, {{"style", "mesh"}, {"props_style", "primitive"}});
  EXPECT_EQ(people_only.actors_style, "mesh");
  EXPECT_EQ(people_only.props_style, "primitive");
  const Scenario props_only =
      load_scenario(kWalking, {{"style", "primitive"}, {"props_style", "mesh"}});
  EXPECT_EQ(props_only.actors_style, "primitive");
  EXPECT_EQ(props_only.props_style, "mesh");
  const std::string error = error_of([] { load_scenario(kWalking, {{"style", "clay"}}); });
  EXPECT_THAT(error, ::testing::HasSubstr("unknown style 'clay' (expected primitive or mesh)"))
      << error;
}

// A profile's keys come first and the scenario's override them; the shipped
// profiles hold their cameras' sourced values.
TEST(ScenarioSensorProfile, ShippedProfilesGiveTheirCamerasValues) {
  const Scenario kinect = load_scenario(kWalking, {{"sensor.profile", "kinect_v1"}});
  EXPECT_DOUBLE_EQ(kinect.sensor.readout, 0.028);
  EXPECT_DOUBLE_EQ(kinect.sensor.baseline, 0.075);
  EXPECT_TRUE(kinect.sensor.exposure_control.automatic);
  EXPECT_EQ(kinect.sensor.colour.bayer, "grbg");
  EXPECT_EQ(kinect.sensor.colour.demosaic, "bilinear");
  EXPECT_EQ(kinect.sensor.colour.jpeg_quality, 0);
  const Scenario d435 =
      load_scenario(kWalking, {{"sensor.profile", "realsense_d435"}, {"sensor.max_gain", "4"}});
  EXPECT_DOUBLE_EQ(d435.sensor.baseline, 0.05);
  EXPECT_DOUBLE_EQ(d435.sensor.min_depth, 0.28);
  EXPECT_DOUBLE_EQ(d435.sensor.exposure_control.max_gain, 4.0);  // the override wins
  EXPECT_DOUBLE_EQ(d435.sensor.colour.full_well, 4300);
}

// Lamps: each needs which light and its events; mistakes are one error
// naming the file and the problem.
TEST(ScenarioLamps, ReadsLampsAndRefusesBadOnes) {
  const Scenario s =
      load_scenario(kWalking, {{"lamps", "[{near: [0, 3], events: [[1, 1], [2, 0.2]]}]"}});
  ASSERT_EQ(s.lamps.size(), 1u);
  EXPECT_EQ(s.lamps[0].near, Eigen::Vector2d(0, 3));
  ASSERT_EQ(s.lamps[0].level.events.size(), 2u);
  EXPECT_DOUBLE_EQ(s.lamps[0].level.events[1].y(), 0.2);
  for (const auto& [value, needle] : std::vector<std::pair<std::string, std::string>>{
           {"[{near: [0, 3]}]", "a lamp needs 'near: [x, y]' (which ceiling light) and 'events'"},
           {"[{near: [0, 3], events: [[2, 1], [1, 0]]}]", "events must be in time order"},
           {"[{near: [0, 3], events: [[1, -1]]}]", "a light level must be within [0, 10]"},
           {"[{near: [0, 3], events: [], colour: red}]", "unknown key 'colour'"},
           {"{near: [0, 3]}", "'lamps' must be a list of {near, events}"}}) {
    const std::string error = error_of([&] { load_scenario(kWalking, {{"lamps", value}}); });
    EXPECT_THAT(error, ::testing::HasSubstr(needle)) << value << ": " << error;
    // Nodes inside the --set value name the option, not a line of the file.
    EXPECT_THAT(error, ::testing::HasSubstr("depot_walking_xyz.yaml: --set lamps=")) << error;
  }
}

// A check between a profile's key and the scenario's own names the scenario's
// setting and the problem (it once failed inside yaml-cpp: "invalid node",
// looking up the line of a key the scenario's sensor map does not hold).
TEST(ScenarioSensorProfile, AConflictWithTheProfileIsOneClearError) {
  const std::string error = error_of([] {
    load_scenario(kWalking, {{"sensor.profile", "kinect_v1"}, {"sensor.max_exposure", "0.008"}});
  });
  EXPECT_NE(error.find("sensor exposure = 0.015000 s is longer than max_exposure = 0.008000 s"),
            std::string::npos)
      << error;
  EXPECT_THAT(error, ::testing::Not(::testing::HasSubstr("invalid node"))) << error;
  EXPECT_THAT(error, ::testing::Not(::testing::HasSubstr(".yaml:0"))) << "no line 0: " << error;
}

}  // namespace
}  // namespace depot::sim
