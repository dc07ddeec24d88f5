// Scenario files the fuzzer made (tests/fuzz/fuzz_scenario): each is one
// error line naming the file and line, never a yaml-cpp exception.
#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/testing/error_of.h"
#include "common/testing/scratch_folder.h"
#include "sim/scenario/scenario_loader.h"

namespace depot::sim {
namespace {

TEST(ScenarioBadInput, AKeyThatIsNotAPlainNameIsOneError) {
  const testkit::ScratchFolder scratch("scenario");
  const std::string path =
      scratch.write("map_key.yaml", "name: x\nmotion: {type: static}\n{a: 1}: 2\n");
  EXPECT_EQ(error_of([&] { load_scenario(path); }), path + ":3: a key must be a plain name");
}

TEST(ScenarioBadInput, AFileThatIsNotAPathIsOneError) {
  const testkit::ScratchFolder scratch("scenario");
  const std::string path =
      scratch.write("scene_list.yaml", "name: x\nmotion: {type: static}\nscene: [a, b]\n");
  EXPECT_EQ(error_of([&] { load_scenario(path); }), path + ":3: bad value for 'scene'");
}

// A plain scalar that runs over several lines inside a flow map keeps its
// line breaks; the error quoting it stays one line (fuzz_scenario, stop 35).
TEST(ScenarioBadInput, AValueQuotedWithItsLineBreaksIsStillOneLine) {
  const testkit::ScratchFolder scratch("scenario");
  const std::string path = scratch.write("multiline.yaml", "name: x\nmotion: {type: w\n\n\n\ne}\n");
  const std::string error = error_of([&] { load_scenario(path); });
  EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  EXPECT_THAT(error, ::testing::HasSubstr("unknown camera motion 'w\\n")) << error;
}

// #27's actors: carriers, the forklift, crowds and doors, each mistake one line.
TEST(ScenarioBadInput, CarriersForkliftsCrowdsAndDoorsMistakesAreOneErrorEach) {
  const testkit::ScratchFolder scratch("scenario");
  const std::string path = scratch.write("carry.yaml", "name: x\nmotion: {type: static}\n");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"actors=[{type: forklift, path: [[0, 0], [1, 0]]}]",
       "forklift 'forklift_0' needs 'carries: pallet' and a 'path'"},
      {"actors=[{type: human, carries: pallet, path: [[0, 0], [1, 0]]}]",
       "actor 'human_0' carries 'pallet' (expected crate or sack)"},
      {"actors=[{type: forklift, carries: crate, path: [[0, 0], [1, 0]]}]",
       "actor 'forklift_0' carries 'crate' (expected pallet)"},
      {"actors=[{type: human, carries: crate, loop: true, path: [[0, 0], [1, 0]]}]",
       "carries its goods out and back: 'loop' must be false"},
      {"actors=[{type: dog, carries: crate, path: [[0, 0], [1, 0]]}]", "only humans can carry"},
      {"actors=[{type: human, pick_height: 1, path: [[0, 0], [1, 0]]}]",
       "pick_height and put_height go with 'carries'"},
      {"actors=[{type: human, carries: crate, pick_height: 3, path: [[0, 0], [1, 0]]}]",
       "'pick_height' = 3 is out of range [0, 2]"},
      {"crowds=[{name: c, count: 5, area: [[1, 1], [0, 0]]}]",
       "crowd 'c': 'area' must be [[x_min, y_min], [x_max, y_max]]"},
      {"crowds=[{name: c, area: [[0, 0], [30, 1]]}]", "crowd 'c': its area is not inside the hall"},
      {"crowds=[{name: c, area: [[0, 0], [1, 1]], goals: home}]",
       "crowd 'c': unknown goals 'home' (expected ends or anywhere)"},
      {"crowds=[{name: c, area: [[0, 0], [1, 1]], speed: [2, 1]}]",
       "crowd 'c': 'speed' must be [low, high] m/s within [0.2, 2.5]"},
      {"doors=[{name: d}]", "door 'd' needs 'hinge: [x, y]'"},
      {"doors=[{name: d, hinge: [30, 0]}]", "door 'd' is not inside the hall"},
      {"doors=[{name: d, hinge: [0, 0], events: [[1, 0], [2, 1.5]]}]",
       "a door's share open must be within [0, 1]"},
      {"doors=[{name: d, hinge: [0, 0], shut: [5, 1]}]",
       "door 'd': 'shut' must be [low, high] s within [0.2, 600]"},
      {"doors=[{name: d, hinge: [0, 0], events: [[1, 0]], open: [1, 2]}]",
       "takes 'events' or seeded 'shut' and 'open' times, not both"},
      {"doors=[{name: d, hinge: [0, 0], width: 9}]", "'width' = 9 is out of range [0.4, 4]"},
  };
  for (const auto& [set, expected] : cases) {
    const size_t eq = set.find('=');
    const std::string error = error_of([&] {
      load_scenario(path, {{set.substr(0, eq), set.substr(eq + 1)}});
    });
    EXPECT_THAT(error, ::testing::HasSubstr(expected)) << set;
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  }
}

TEST(ScenarioBadInput, ShutterTimesOutOfRangeAreOneError) {
  const testkit::ScratchFolder scratch("scenario");
  const std::string negative = scratch.write(
      "exposure.yaml", "name: x\nmotion: {type: static}\nsensor: {exposure: -0.01}\n");
  EXPECT_EQ(error_of([&] { load_scenario(negative); }),
            negative + ":3: 'exposure' = -0.01 is out of range [0, 0.5]");
  // A readout longer than a frame: the rows are read once per frame.
  const std::string long_readout = scratch.write(
      "readout.yaml",
      "name: x\nmotion: {type: static}\nsensor: {exposure: 0.02,\n  readout: 0.04}\n");
  EXPECT_EQ(
      error_of([&] { load_scenario(long_readout); }),
      long_readout + ":4: sensor readout = 40.0 ms is longer than a frame (33.3 ms at 30 Hz)");
  // The same through --set, blamed on the option.
  const std::string fine =
      scratch.write("fine.yaml", "name: x\nmotion: {type: static}\nsensor: {exposure: 0.02}\n");
  EXPECT_EQ(error_of([&] {
              load_scenario(fine, {{"sensor.readout", "0.04"}});
            }),
            fine +
                ": --set sensor.readout=0.04: sensor readout = 40.0 ms is longer than a frame "
                "(33.3 ms at 30 Hz)");
  // Together they may span more than a frame (sim/world/world.h checkpoints).
  EXPECT_NO_THROW(load_scenario(fine, {{"sensor.readout", "0.03"}}));
}

TEST(ScenarioBadInput, TimingAndDepthClockOutOfRangeAreOneError) {
  const testkit::ScratchFolder scratch("scenario");
  const std::string far_depth = scratch.write(
      "depth_offset.yaml", "name: x\nmotion: {type: static}\nsensor: {depth_offset: 0.02}\n");
  EXPECT_EQ(error_of([&] { load_scenario(far_depth); }),
            far_depth + ":3: sensor depth_offset = 20.0 ms is more than a quarter frame (8.3 ms)");
  const std::string drops = scratch.write(
      "drop_rate.yaml", "name: x\nmotion: {type: static}\ntimestamps: {drop_rate: 1.5}\n");
  EXPECT_EQ(error_of([&] { load_scenario(drops); }),
            drops + ":3: 'drop_rate' = 1.5 is out of range [0, 0.9]");
}

// Light, exposure control, the colour pipeline and sensor profiles: each
// mistake is one line naming the file and line.
TEST(ScenarioBadInput, LightExposureAndColourMistakesAreOneError) {
  const testkit::ScratchFolder scratch("scenario");
  const struct {
    std::string sensor, error;
  } cases[] = {
      {"{light: -0.5}", ":3: 'light' = -0.5 is out of range [0, 10]"},
      {"{light_events: [[1, 1], [0.5, 0.2]]}", ":3: light_events must be in time order"},
      {"{light_events: [[1, 1], [2]]}", ":3: a light event must be [time, level]"},
      {"{light_events: 3}", ":3: 'light_events' must be a list of [time, level]"},
      {"{light_events: [[1, 20]]}", ":3: a light level must be within [0, 10]"},
      {"{flicker: 1.5}", ":3: 'flicker' = 1.5 is out of range [0, 1]"},
      {"{auto_exposure: true}",
       ":3: auto_exposure starts from the sensor's 'exposure' (the exposure the render stands "
       "for): set exposure > 0"},
      {"{auto_exposure: yes please, exposure: 0.01}", ":3: bad value for 'auto_exposure'"},
      {"{auto_exposure: true, exposure: 0.02, max_exposure: 0.01}",
       ":3: sensor exposure = 0.020000 s is longer than max_exposure = 0.010000 s"},
      {"{auto_exposure: true, exposure: 0.01, max_exposure: 0.04, readout: 0.01}",
       ":3: sensor max_exposure = 40.0 ms is longer than a frame (33.3 ms at 30 Hz)"},
      {"{vignetting: 0}", ":3: 'vignetting' = 0 is out of range [0.05, 1]"},
      {"{demosaic: vng}", ":3: unknown demosaic 'vng' (expected none, bilinear or edge_aware)"},
      {"{motion_blur: flow}", ":3: unknown motion_blur 'flow' (expected subframes or field)"},
      {"{bayer: rgbg}", ":3: unknown bayer pattern 'rgbg' (expected rggb, grbg, gbrg or bggr)"},
      {"{full_well: 50}",
       ":3: 'full_well' must be 0 (no sensor noise model) or at least 100 electrons"},
      {"{jpeg_quality: 101}", ":3: 'jpeg_quality' = 101 is out of range [0, 100]"},
      {"{profile: no_such_camera}", ":3: unknown sensor profile 'no_such_camera' (no "},
  };
  for (const auto& c : cases) {
    const std::string path =
        scratch.write("colour.yaml", "name: x\nmotion: {type: static}\nsensor: " + c.sensor + "\n");
    const std::string error = error_of([&] { load_scenario(path); });
    EXPECT_EQ(error.substr(0, path.size() + c.error.size()), path + c.error) << c.sensor;
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  }
}

// A profile's keys come first; the scenario's own keys override them; a
// mistake inside a profile names the profile's file and line.
TEST(ScenarioBadInput, ProfilesAreReadFirstAndTheirMistakesNameTheirFile) {
  const testkit::ScratchFolder scratch("scenario");
  const std::string profile = scratch.write(
      "camera_profile.yaml", "# a camera\nsensor:\n  rgb_noise: 1.5\n  vignetting: 0.7\n");
  const std::string path = scratch.write(
      "profiled.yaml",
      "name: x\nmotion: {type: static}\nsensor: {profile: " + profile + ", vignetting: 0.9}\n");
  const Scenario s = load_scenario(path);
  EXPECT_DOUBLE_EQ(s.sensor.rgb_noise, 1.5);
  EXPECT_DOUBLE_EQ(s.sensor.colour.vignetting, 0.9);
  const std::string bad = scratch.write("bad_profile.yaml", "sensor:\n  lens_blur: -1\n");
  const std::string uses_bad = scratch.write(
      "uses_bad.yaml", "name: x\nmotion: {type: static}\nsensor: {profile: " + bad + "}\n");
  EXPECT_EQ(error_of([&] { load_scenario(uses_bad); }),
            bad + ":2: 'lens_blur' = -1 is out of range [0, 10]");
}

}  // namespace
}  // namespace depot::sim
