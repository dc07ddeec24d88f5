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

}  // namespace
}  // namespace depot::sim
