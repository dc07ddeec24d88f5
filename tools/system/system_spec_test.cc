// System files: what a command may name, what a bad file says, and how a
// name or path finds its file.
#include "tools/system/system_spec.h"

#include <filesystem>
#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/error.h"
#include "common/testing/scratch_folder.h"

namespace fs = std::filesystem;

namespace depot::system {
namespace {

// The file's name (so the system's) is depot_system_spec_<name>.
std::string write_system(const testkit::ScratchFolder& scratch, const std::string& name,
                         const std::string& text) {
  return scratch.write("depot_system_spec_" + name + ".yaml", text);
}

std::string load_error(const testkit::ScratchFolder& scratch, const std::string& name,
                       const std::string& text) {
  try {
    load_system_spec(write_system(scratch, name, text));
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(SystemSpec, LoadsAndExpandsACommand) {
  const testkit::ScratchFolder scratch("system_spec");
  const SystemSpec spec = load_system_spec(write_system(scratch, "good", R"(
description: a test system
command: [/usr/bin/env, "--dataset={dataset}", "{trajectory}", "{keypoints}", "awk { print }"]
trajectory_format: euroc
time_limit_s: 2.5
env: {OMP_NUM_THREADS: "1"}
)"));
  EXPECT_EQ(spec.name, "depot_system_spec_good");
  EXPECT_EQ(spec.trajectory_format, TrajectoryFormat::kEuroc);
  EXPECT_DOUBLE_EQ(spec.time_limit_s, 2.5);
  EXPECT_EQ(spec.env.at("OMP_NUM_THREADS"), "1");
  EXPECT_TRUE(spec.writes_keypoints);
  const std::vector<std::string> argv =
      expand_command(spec, {{"dataset", "/d"}, {"trajectory", "/t.csv"}, {"keypoints", "/k.csv"}});
  const std::vector<std::string> expected = {"/usr/bin/env", "--dataset=/d", "/t.csv", "/k.csv",
                                             "awk { print }"};
  EXPECT_EQ(argv, expected);  // braces that are no placeholder stay text
}

TEST(SystemSpec, BadFilesNameTheFileAndTheProblem) {
  const testkit::ScratchFolder scratch("system_spec");
  EXPECT_NE(load_error(scratch, "placeholder", "command: [x, \"{trajectory}\", \"{frames}\"]\n")
                .find(":1: unknown placeholder '{frames}'"),
            std::string::npos);
  EXPECT_NE(load_error(scratch, "no_trajectory", "command: [x, \"{dataset}\"]\n")
                .find("never names {trajectory}"),
            std::string::npos);
  EXPECT_NE(load_error(scratch, "no_command", "trajectory_format: tum\n").find("no command"),
            std::string::npos);
  EXPECT_THAT(load_error(scratch, "empty_command", "command: []\n"),
              ::testing::HasSubstr("non-empty list"));
  EXPECT_NE(
      load_error(scratch, "format", "command: [x, \"{trajectory}\"]\ntrajectory_format: g2o\n")
          .find(":2: unknown trajectory_format 'g2o'"),
      std::string::npos);
  EXPECT_NE(load_error(scratch, "limit", "command: [x, \"{trajectory}\"]\ntime_limit_s: 0\n")
                .find("time_limit_s must be in (0, 86400]"),
            std::string::npos);
  EXPECT_NE(load_error(scratch, "timestamps", "command: [x, \"{trajectory}\", \"{timestamps}\"]\n")
                .find("{timestamps} is for a KITTI trajectory"),
            std::string::npos);
  EXPECT_NE(load_error(scratch, "key", "command: [x, \"{trajectory}\"]\ntimeout: 5\n")
                .find("unknown key 'timeout'"),
            std::string::npos);
  EXPECT_NE(load_error(scratch, "list", "- a\n- b\n").find("a system file is a YAML map"),
            std::string::npos);
}

// Found by fuzzing (tests/fuzz/fuzz_system_spec): text of the file quoted
// in an error kept its newlines, so the error was more than one line.
TEST(SystemSpec, AnErrorQuotingTheFileIsOneLine) {
  const testkit::ScratchFolder scratch("system_spec");
  // yaml-cpp's message quotes the character after the backslash, here NUL.
  const char escape[] = "command: [x, \"{trajectory}\"]\nenv: \"\\\0\"\n";
  const std::string syntax = load_error(scratch, "escape", std::string(escape, sizeof(escape) - 1));
  EXPECT_NE(syntax.find("depot_system_spec_escape.yaml:2: YAML syntax error: unknown escape "
                        "character: \\x00"),
            std::string::npos)
      << syntax;
  const std::string format =
      load_error(scratch, "format_newline",
                 "command: [x, \"{trajectory}\"]\ntrajectory_format: \"a\\nb\\x01\"\n");
  EXPECT_NE(format.find(":2: unknown trajectory_format 'a\\nb\\x01' (expected tum, kitti, euroc)"),
            std::string::npos)
      << format;
  const std::string key =
      load_error(scratch, "key_newline", "command: [x, \"{trajectory}\"]\n\"a\\nb\": 1\n");
  EXPECT_NE(key.find(":2: unknown key 'a\\nb' (expected"), std::string::npos) << key;
  EXPECT_EQ(key.find('\n'), std::string::npos) << key;
}

TEST(SystemSpec, NamesFindShippedFilesAndPathsFindTheirs) {
  const testkit::ScratchFolder scratch("system_spec");
  EXPECT_TRUE(is_system_mode("system:open3d_odometry"));
  EXPECT_FALSE(is_system_mode("full"));
  EXPECT_EQ(system_of_mode("system:my/own.yaml"), "my/own.yaml");
  const std::string shipped = find_system_file("open3d_odometry");
  EXPECT_EQ(fs::path(shipped).filename(), "open3d_odometry.yaml");
  EXPECT_NO_THROW(load_system_spec(shipped));
  EXPECT_NO_THROW(load_system_spec(find_system_file("depot_masked")));
  const std::string own = write_system(scratch, "own", "command: [x, \"{trajectory}\"]\n");
  EXPECT_EQ(find_system_file(own), own);
  EXPECT_THROW(find_system_file("no_such_system"), Error);
  EXPECT_THROW(find_system_file("/no/such/system.yaml"), Error);
}

}  // namespace
}  // namespace depot::system
