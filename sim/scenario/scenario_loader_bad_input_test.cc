// Scenario files the fuzzer made (tests/fuzz/fuzz_scenario): each is one
// error line naming the file and line, never a yaml-cpp exception.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "common/testing/error_of.h"
#include "sim/scenario/scenario_loader.h"

namespace depot::sim {
namespace {

std::string write_scenario(const std::string& name, const std::string& text) {
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("depot_scenario_" + std::to_string(::getpid()) + "_" + name))
                               .string();
  std::ofstream(path) << text;
  return path;
}

TEST(ScenarioBadInput, AKeyThatIsNotAPlainNameIsOneError) {
  const std::string path =
      write_scenario("map_key.yaml", "name: x\nmotion: {type: static}\n{a: 1}: 2\n");
  EXPECT_EQ(error_of([&] { load_scenario(path); }), path + ":3: a key must be a plain name");
  std::filesystem::remove(path);
}

TEST(ScenarioBadInput, AFileThatIsNotAPathIsOneError) {
  const std::string path =
      write_scenario("scene_list.yaml", "name: x\nmotion: {type: static}\nscene: [a, b]\n");
  EXPECT_EQ(error_of([&] { load_scenario(path); }), path + ":3: bad value for 'scene'");
  std::filesystem::remove(path);
}

// A plain scalar that runs over several lines inside a flow map keeps its
// line breaks; the error quoting it stays one line (fuzz_scenario, stop 35).
TEST(ScenarioBadInput, AValueQuotedWithItsLineBreaksIsStillOneLine) {
  const std::string path =
      write_scenario("multiline.yaml", "name: x\nmotion: {type: w\n\n\n\ne}\n");
  const std::string error = error_of([&] { load_scenario(path); });
  EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  EXPECT_NE(error.find("unknown camera motion 'w\\n"), std::string::npos) << error;
  std::filesystem::remove(path);
}

TEST(ScenarioBadInput, ShutterTimesOutOfRangeAreOneError) {
  const std::string negative = write_scenario(
      "exposure.yaml", "name: x\nmotion: {type: static}\nsensor: {exposure: -0.01}\n");
  EXPECT_EQ(error_of([&] { load_scenario(negative); }),
            negative + ":3: 'exposure' = -0.010000 is out of range [0.000000, 0.500000]");
  std::filesystem::remove(negative);
  // Exposure and readout together longer than a frame: the next frame's
  // first row would start before this one's last ended.
  const std::string long_readout = write_scenario(
      "readout.yaml",
      "name: x\nmotion: {type: static}\nsensor: {exposure: 0.02,\n  readout: 0.02}\n");
  EXPECT_EQ(
      error_of([&] { load_scenario(long_readout); }),
      long_readout +
          ":4: sensor exposure + readout = 40.0 ms is longer than a frame (33.3 ms at 30 Hz)");
  // The same through --set, blamed on the option.
  const std::string fine =
      write_scenario("fine.yaml", "name: x\nmotion: {type: static}\nsensor: {exposure: 0.02}\n");
  EXPECT_EQ(error_of([&] {
              load_scenario(fine, {{"sensor.readout", "0.02"}});
            }),
            fine +
                ": --set sensor.readout=0.02: sensor exposure + readout = 40.0 ms is longer than a "
                "frame (33.3 ms at 30 Hz)");
  EXPECT_NO_THROW(load_scenario(fine, {{"sensor.readout", "0.013"}}));
  std::filesystem::remove(long_readout);
  std::filesystem::remove(fine);
}

TEST(ScenarioBadInput, TimingAndDepthClockOutOfRangeAreOneError) {
  const std::string far_depth = write_scenario(
      "depth_offset.yaml", "name: x\nmotion: {type: static}\nsensor: {depth_offset: 0.02}\n");
  EXPECT_EQ(error_of([&] { load_scenario(far_depth); }),
            far_depth + ":3: sensor depth_offset = 20.0 ms is more than a quarter frame (8.3 ms)");
  const std::string drops = write_scenario(
      "drop_rate.yaml", "name: x\nmotion: {type: static}\ntimestamps: {drop_rate: 1.5}\n");
  EXPECT_EQ(error_of([&] { load_scenario(drops); }),
            drops + ":3: 'drop_rate' = 1.500000 is out of range [0.000000, 0.900000]");
  std::filesystem::remove(far_depth);
  std::filesystem::remove(drops);
}

}  // namespace
}  // namespace depot::sim
