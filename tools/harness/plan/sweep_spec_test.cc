#include "tools/harness/plan/sweep_spec.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/error.h"
#include "common/testing/error_of.h"

namespace depot::harness {
namespace {

SweepSpec small_spec() {
  SweepSpec s;
  s.scenarios = {{"depot_walking_xyz", "/x/depot_walking_xyz.yaml"}};
  s.vary = {parse_sweep_parameter("load=0, 0.5,1", "--vary")};
  s.fixed = {parse_sweep_parameter("miss_rate=0.1", "--set")};
  s.modes = {"orb", "full"};
  s.seeds = 2;
  s.frames = 40;
  s.width = 160;
  return s;
}

TEST(SweepSpec, ParsesLevelsAndResolvesAliases) {
  const SweepParameter p = parse_sweep_parameter("load=0, 0.5,1", "--vary");
  EXPECT_EQ(p.name, "load");
  EXPECT_EQ(p.values, (std::vector<std::string>{"0", "0.5", "1"}));
  EXPECT_EQ(resolve_parameter("load").key, "dynamic_load");
  EXPECT_EQ(resolve_parameter("latency").target, ParameterTarget::kDetector);
  EXPECT_EQ(resolve_parameter("latency").key, "latency_frames");
  EXPECT_EQ(resolve_parameter("scenario.sensor.rgb_noise").key, "sensor.rgb_noise");
  EXPECT_EQ(resolve_parameter("exposure").key, "sensor.exposure");
  EXPECT_EQ(resolve_parameter("readout").key, "sensor.readout");
  EXPECT_EQ(resolve_parameter("distortion").key, "sensor.k1");
  EXPECT_EQ(resolve_parameter("light").key, "sensor.light");
  EXPECT_EQ(resolve_parameter("detector.jitter").target, ParameterTarget::kDetector);
  EXPECT_EQ(resolve_parameter("rejection.ego_flow").target, ParameterTarget::kRejection);
  EXPECT_EQ(resolve_parameter("rejection.ego_flow").key, "ego_flow");
}

TEST(SweepSpec, RejectsUnknownNamesAndBadGrids) {
  EXPECT_NE(error_of([] { resolve_parameter("speed"); }).find("unknown parameter 'speed'"),
            std::string::npos);
  EXPECT_THROW(parse_sweep_parameter("load=0,,1", "--vary"), Error);
  EXPECT_THROW(parse_sweep_parameter("load", "--vary"), Error);
  SweepSpec s = small_spec();
  s.modes = {"orb", "orb"};
  EXPECT_THAT(error_of([&] { validate(s, "x"); }), ::testing::HasSubstr("given twice"));
  s = small_spec();
  s.vary[0].values = {"1", "1"};
  EXPECT_THAT(error_of([&] { validate(s, "x"); }), ::testing::HasSubstr("repeats a level"));
  s = small_spec();
  s.fixed.push_back({"load", {"2"}});
  EXPECT_THAT(error_of([&] { validate(s, "x"); }), ::testing::HasSubstr("set the same thing"));
  s = small_spec();  // an alias and its full name reach one setting
  s.vary.push_back({"scenario.dynamic_load", {"2"}});
  EXPECT_NE(error_of([&] { validate(s, "x"); }).find("'load' and 'scenario.dynamic_load'"),
            std::string::npos);
  s = small_spec();  // a key and a key inside it
  s.vary = {{"scenario.sensor", {"{}"}}, {"rgb_noise", {"1"}}};
  EXPECT_THAT(error_of([&] { validate(s, "x"); }), ::testing::HasSubstr("set the same thing"));
  s = small_spec();
  s.modes = {"orb+slam"};
  EXPECT_THAT(error_of([&] { validate(s, "x"); }), ::testing::HasSubstr("unknown mode"));
}

TEST(SweepSpec, SurvivesAJsonRoundTrip) {
  const SweepSpec s = small_spec();
  const SweepSpec back = sweep_spec_from_json(to_json(s), "sweep.json");
  EXPECT_EQ(to_json(back), to_json(s));
  nlohmann::json broken = to_json(s);
  broken.erase("modes");
  EXPECT_NE(error_of([&] { sweep_spec_from_json(broken, "sweep.json"); }).find("sweep.json"),
            std::string::npos);
}

}  // namespace
}  // namespace depot::harness
