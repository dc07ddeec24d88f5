#include "common/staged_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/error.h"
#include "common/testing/scratch_folder.h"

namespace fs = std::filesystem;

namespace depot {
namespace {

size_t entries(const fs::path& dir) {
  size_t n = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++n;
  return n;
}

TEST(StagedFile, AppearsWholeOnCommitAndNotAtAllOtherwise) {
  const testkit::ScratchFolder scratch("staged_file_commit");
  const fs::path& dir = scratch.path();
  const fs::path out = dir / "stats.csv";
  {
    StagedFile file(out.string());
    file.stream() << "a,b\n1,2\n";
    EXPECT_FALSE(fs::exists(out));
    EXPECT_EQ(entries(dir), 1u);  // only the hidden partial file
    file.commit();
  }
  std::ifstream in(out);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), "a,b\n1,2\n");
  EXPECT_EQ(entries(dir), 1u);

  // A run that fails before commit leaves nothing, not even the partial file.
  const fs::path failed = dir / "failed.csv";
  try {
    StagedFile file(failed.string());
    file.stream() << "half";
    throw Error("run failed");
  } catch (const Error&) {
  }
  EXPECT_FALSE(fs::exists(failed));
  EXPECT_EQ(entries(dir), 1u);
}

TEST(StagedFile, AnUnwritableFolderIsAClearError) {
  try {
    StagedFile file("/nonexistent/folder/stats.csv");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_THAT(std::string(e.what()), ::testing::HasSubstr("/nonexistent/folder/stats.csv"))
        << e.what();
  }
}

}  // namespace
}  // namespace depot
