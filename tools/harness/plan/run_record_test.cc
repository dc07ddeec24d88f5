#include "tools/harness/plan/run_record.h"

#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>

namespace depot::harness {
namespace {

namespace fs = std::filesystem;

const fs::path kScratch = fs::path(::testing::TempDir()) / "run_record_test";

fs::path scratch_file(const std::string& name) {
  fs::create_directories(kScratch);
  return kScratch / name;
}

TEST(RunRecord, TheScoreOverKeypointsWithDepthRoundTripsAndOlderRecordsHaveNone) {
  RunRecord r;
  r.id = "walk__s1__masked";
  r.mode = "masked";
  r.seed = 1;
  r.precision = 0.9;
  r.recall = 0.8;
  r.precision_with_depth = 0.93;
  r.recall_with_depth = 0.82;
  const fs::path path = scratch_file("with_depth.json");
  write_record(path.string(), to_json(r));
  const RunRecord back = read_run_record(path.string());
  EXPECT_DOUBLE_EQ(back.precision_with_depth, 0.93);
  EXPECT_DOUBLE_EQ(back.recall_with_depth, 0.82);
  // A record written before the score existed reads back without it.
  nlohmann::json old = to_json(r);
  old.at("rejection").erase("with_depth");
  const fs::path old_path = scratch_file("older.json");
  write_record(old_path.string(), old);
  const RunRecord older = read_run_record(old_path.string());
  EXPECT_DOUBLE_EQ(older.recall, 0.8);
  EXPECT_TRUE(std::isnan(older.precision_with_depth));
  EXPECT_TRUE(std::isnan(older.recall_with_depth));
  fs::remove_all(kScratch);
}

}  // namespace
}  // namespace depot::harness
