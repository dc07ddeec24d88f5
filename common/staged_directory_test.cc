#include "common/staged_directory.h"

#include <filesystem>
#include <fstream>

#include <unistd.h>

#include <gtest/gtest.h>

#include "common/error.h"

namespace fs = std::filesystem;

namespace depot {
namespace {

fs::path fresh(const std::string& name) {
  fs::path p = fs::temp_directory_path() / ("depot_staged_" + name);
  fs::remove_all(p);
  return p;
}

TEST(StagedDirectory, AppearsOnlyWhenCommitted) {
  fs::path out = fresh("commit");
  {
    StagedDirectory dir(out.string(), false);
    std::ofstream(fs::path(dir.path()) / "a.txt") << "x";
    EXPECT_FALSE(fs::exists(out));
    dir.commit();
  }
  EXPECT_TRUE(fs::exists(out / "a.txt"));
}

TEST(StagedDirectory, FailureLeavesNothing) {
  fs::path out = fresh("abort");
  std::string staging;
  try {
    StagedDirectory dir(out.string(), false);
    staging = dir.path();
    std::ofstream(fs::path(dir.path()) / "a.txt") << "x";
    throw Error("simulated failure");
  } catch (const Error&) {
  }
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(staging));
}

TEST(StagedDirectory, RefusesNonEmptyOutputUnlessOverwrite) {
  fs::path out = fresh("exists");
  fs::create_directories(out);
  std::ofstream(out / "keep.txt") << "x";
  EXPECT_THROW(StagedDirectory(out.string(), false), Error);
  EXPECT_TRUE(fs::exists(out / "keep.txt"));
  StagedDirectory dir(out.string(), true);
  dir.commit();
  EXPECT_FALSE(fs::exists(out / "keep.txt"));
}

TEST(StagedDirectory, UnwritableParentIsAnError) {
  if (geteuid() == 0) {
    // root can write anywhere; use a path under a regular file instead.
    fs::path file = fresh("file");
    std::ofstream(file) << "x";
    EXPECT_THROW(StagedDirectory((file / "out").string(), false), Error);
  } else {
    EXPECT_THROW(StagedDirectory("/proc/depot_out", false), Error);
  }
}

}  // namespace
}  // namespace depot
