#include "common/staged_directory.h"

#include <filesystem>
#include <fstream>

#include <sys/wait.h>
#include <unistd.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/error.h"
#include "common/staged_file.h"
#include "common/staged_names.h"
#include "common/testing/error_of.h"
#include "common/testing/scratch_folder.h"

namespace fs = std::filesystem;

namespace depot {
namespace {

const OutputKind kKind{"test output", "marker.json", {"marker.json", "a.txt", "data"}};

// A path not yet made, in the test's scratch folder.
fs::path fresh(const testkit::ScratchFolder& scratch, const std::string& name) {
  return scratch.path() / ("depot_staged_" + name);
}

TEST(StagedDirectory, AppearsOnlyWhenCommitted) {
  const testkit::ScratchFolder scratch("staged_commit");
  fs::path out = fresh(scratch, "commit");
  {
    StagedDirectory dir(out.string(), kKind, false);
    std::ofstream(fs::path(dir.path()) / "a.txt") << "x";
    EXPECT_FALSE(fs::exists(out));
    dir.commit();
  }
  EXPECT_TRUE(fs::exists(out / "a.txt"));
}

TEST(StagedDirectory, FailureLeavesNothing) {
  const testkit::ScratchFolder scratch("staged_abort");
  fs::path out = fresh(scratch, "abort");
  std::string staging;
  try {
    StagedDirectory dir(out.string(), kKind, false);
    staging = dir.path();
    std::ofstream(fs::path(dir.path()) / "a.txt") << "x";
    throw Error("simulated failure");
  } catch (const Error&) {
  }
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(staging));
}

TEST(StagedDirectory, RefusesNonEmptyOutputUnlessOverwrite) {
  const testkit::ScratchFolder scratch("staged_exists");
  fs::path out = fresh(scratch, "exists");
  fs::create_directories(out);
  std::ofstream(out / "keep.txt") << "x";
  EXPECT_THROW(StagedDirectory(out.string(), kKind, false), Error);
  EXPECT_TRUE(fs::exists(out / "keep.txt"));
  // Not ours (no marker): refused even with overwrite.
  EXPECT_NE(error_of([&] { StagedDirectory(out.string(), kKind, true); }).find("no marker.json"),
            std::string::npos);
  EXPECT_TRUE(fs::exists(out / "keep.txt"));
}

TEST(StagedDirectory, OverwriteReplacesOnlyAnOutputOfItsKind) {
  const testkit::ScratchFolder scratch("staged_ours");
  fs::path out = fresh(scratch, "ours");
  fs::create_directories(out / "data");
  std::ofstream(out / "marker.json") << "{}";
  std::ofstream(out / "a.txt") << "old";
  {
    StagedDirectory dir(out.string(), kKind, true);
    std::ofstream(fs::path(dir.path()) / "marker.json") << "{}";
    std::ofstream(fs::path(dir.path()) / "a.txt") << "new";
    EXPECT_TRUE(fs::exists(out / "data")) << "the old output stays until the new one is whole";
    dir.commit();
  }
  std::ifstream in(out / "a.txt");
  std::string text;
  in >> text;
  EXPECT_EQ(text, "new");
  EXPECT_FALSE(fs::exists(out / "data"));
  for (const auto& e : fs::directory_iterator(out.parent_path()))
    EXPECT_THAT(e.path().string(), ::testing::Not(::testing::HasSubstr("depot_staged_ours.")))
        << e.path();

  // A file the kind never writes makes the folder the user's.
  std::ofstream(out / "notes.txt") << "mine";
  EXPECT_NE(error_of([&] { StagedDirectory(out.string(), kKind, true); }).find("notes.txt"),
            std::string::npos);
  EXPECT_TRUE(fs::exists(out / "notes.txt"));
}

TEST(StagedDirectory, RefusesTheCurrentFolderAndItsParents) {
  const testkit::ScratchFolder scratch("staged_cwd");
  fs::path out = fresh(scratch, "cwd");
  fs::create_directories(out / "inner");
  std::ofstream(out / "marker.json") << "{}";
  const fs::path before = fs::current_path();
  fs::current_path(out / "inner");
  const std::string error = error_of([&] { StagedDirectory(out.string(), kKind, true); });
  const std::string error_dot = error_of([&] { StagedDirectory(".", kKind, true); });
  fs::current_path(before);
  EXPECT_THAT(error, ::testing::HasSubstr("current folder")) << error;
  EXPECT_THAT(error_dot, ::testing::HasSubstr("current folder")) << error_dot;
  EXPECT_TRUE(fs::exists(out / "inner"));
}

TEST(StagedDirectory, RemovesPartialFoldersOfDeadProcessesOnly) {
  const testkit::ScratchFolder scratch("staged_stale");
  fs::path out = fresh(scratch, "stale");
  const pid_t child = fork();
  if (child == 0) _exit(0);
  int status = 0;
  waitpid(child, &status, 0);  // a pid whose process is gone
  const fs::path dead = out.string() + ".partial-" + std::to_string(child);
  const fs::path live = out.string() + ".partial-" + std::to_string(getppid());
  fs::create_directories(dead);
  fs::create_directories(live);
  std::ofstream(dead / "a.txt") << "x";
  {
    StagedDirectory dir(out.string(), kKind, false);
    EXPECT_FALSE(fs::exists(dead));
    EXPECT_TRUE(fs::exists(live));
  }
}

TEST(StagedDirectory, PutsBackAnOutputMovedAsideByAKilledCommit) {
  const testkit::ScratchFolder scratch("staged_aside");
  fs::path out = fresh(scratch, "aside");
  const pid_t child = fork();
  if (child == 0) _exit(0);
  int status = 0;
  waitpid(child, &status, 0);
  const fs::path aside = out.string() + ".replaced-" + std::to_string(child);
  fs::remove_all(aside);
  fs::create_directories(aside);
  std::ofstream(aside / "marker.json") << "{}";
  { StagedDirectory dir(out.string(), kKind, false); }
  EXPECT_TRUE(fs::exists(out / "marker.json"));
  EXPECT_FALSE(fs::exists(aside));
}

TEST(StagedDirectory, UnwritableParentIsAnError) {
  if (geteuid() == 0) {
    // root can write anywhere; use a path under a regular file instead.
    const testkit::ScratchFolder scratch("staged_file");
    fs::path file = fresh(scratch, "file");
    std::ofstream(file) << "x";
    EXPECT_THROW(StagedDirectory((file / "out").string(), kKind, false), Error);
  } else {
    EXPECT_THROW(StagedDirectory("/proc/depot_out", kKind, false), Error);
  }
}

}  // namespace
}  // namespace depot

namespace depot {
namespace {

// An error met inside a staged folder or file names a temporary path that
// is gone once the failure unwinds; the line a user reads names the final one.
TEST(StagedNames, ErrorsNameTheFinalPathNotTheStagedOne) {
  const testkit::ScratchFolder scratch("staged_names");
  const fs::path out = fresh(scratch, "names");
  std::string message;
  try {
    StagedDirectory dir(out.string(), kKind, false);
    StagedFile inside((fs::path(dir.path()) / "a.txt").string());
    throw Error((fs::path(dir.path()) / "data/0001.png").string() + ": cannot write; " +
                inside.final_path() + " too");
  } catch (const Error& e) {
    message = with_final_names(e.what());
  }
  EXPECT_EQ(message, (out / "data/0001.png").string() + ": cannot write; " +
                         (out / "a.txt").string() + " too");
  EXPECT_THAT(message, ::testing::Not(::testing::HasSubstr(".partial-"))) << message;
  EXPECT_EQ(with_final_names("no path here"), "no path here");
}

}  // namespace
}  // namespace depot
