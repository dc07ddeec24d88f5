#include "tools/harness/job/sweep_jobs.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "common/testing/scratch_folder.h"

namespace fs = std::filesystem;

namespace depot::harness {
namespace {

// A camera moving along a circle for 6 s at 10 Hz.
std::vector<StampedPose> circle() {
  std::vector<StampedPose> out;
  for (int i = 0; i < 60; ++i) {
    StampedPose p;
    p.timestamp = 100.0 + 0.1 * i;
    p.pose.translation() = Eigen::Vector3d(std::cos(0.1 * i), std::sin(0.1 * i), 0.02 * i);
    out.push_back(p);
  }
  return out;
}

TEST(SweepJobs, AccuracyOfARunAndOfOneThatLostTheCamera) {
  const testkit::ScratchFolder scratch("jobs_test");
  const fs::path& plot = scratch.path();
  const std::vector<StampedPose> truth = circle();

  // The same motion in another frame (SLAM starts at the identity): ATE 0
  // after alignment, plus a known offset on every second pose.
  std::vector<StampedPose> estimate = truth;
  Pose frame = Pose::Identity();
  frame.translate(Eigen::Vector3d(3, -1, 2));
  frame.rotate(Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()));
  for (size_t i = 0; i < estimate.size(); ++i) {
    estimate[i].pose = frame * truth[i].pose;
    if (i % 2) estimate[i].pose.translation() += frame.linear() * Eigen::Vector3d(0, 0, 0.01);
  }
  RunRecord r;
  r.mode = "full";
  add_accuracy(truth, estimate, (plot / "ate.svg").string(), r);
  EXPECT_TRUE(r.ok);
  EXPECT_NEAR(r.ate_rmse, 0.005, 1e-3);  // +-5 mm about the fitted middle
  EXPECT_TRUE(std::isfinite(r.rpe_trans_rmse));
  EXPECT_TRUE(fs::is_regular_file(plot / "ate.svg"));

  // Two poses left after a loss: recorded as an outcome, not thrown.
  RunRecord lost;
  lost.mode = "orb";
  const std::vector<StampedPose> two(estimate.end() - 2, estimate.end());
  EXPECT_NO_THROW(add_accuracy(truth, two, (plot / "lost.svg").string(), lost));
  EXPECT_FALSE(lost.ok);
  EXPECT_THAT(lost.error, ::testing::HasSubstr("too few to evaluate")) << lost.error;
  EXPECT_TRUE(std::isnan(lost.ate_rmse));
  EXPECT_FALSE(fs::exists(plot / "lost.svg"));
}

// The atlas's figures: half the frames in the trajectory's map, a quarter
// in a map of its own frame, the rest lost; each map aligns to zero.
TEST(SweepJobs, AtlasAccuracyCountsTheFramesOfEveryMap) {
  const std::vector<StampedPose> truth = circle();
  Pose other = Pose::Identity();
  other.translate(Eigen::Vector3d(1, 2, 3));
  other.rotate(Eigen::AngleAxisd(1.1, Eigen::Vector3d::UnitX()));
  std::vector<StampedPose> atlas;
  std::vector<slam::StampedFrameState> states;
  const size_t n = truth.size();
  for (size_t i = 0; i < n; ++i) {
    if (i < n / 2) {
      atlas.push_back(truth[i]);
      states.push_back({truth[i].timestamp, slam::FrameState::kOk, 0});
    } else if (i < 3 * n / 4) {
      atlas.push_back({truth[i].timestamp, other * truth[i].pose});
      states.push_back({truth[i].timestamp, slam::FrameState::kOtherMap, 1});
    } else {
      states.push_back({truth[i].timestamp, slam::FrameState::kLost, -1});
    }
  }
  RunRecord r;
  r.mode = "full";
  r.tracked = static_cast<int>(n / 2);
  add_atlas_accuracy(truth, atlas, states, r);
  EXPECT_EQ(r.posed, static_cast<int>(atlas.size()));
  EXPECT_EQ(r.maps, 2);
  EXPECT_LT(r.ate_all_maps_rmse, 1e-9);
  // Read back from the record.
  const testkit::ScratchFolder scratch("atlas_record");
  const fs::path file = scratch.path() / "atlas_record";
  write_record(file.string(), to_json(r));
  const RunRecord back = read_run_record(file.string());
  EXPECT_EQ(back.posed, r.posed);
  EXPECT_EQ(back.maps, 2);
  EXPECT_LT(back.ate_all_maps_rmse, 1e-9);
  // Another system's states name no maps: its trajectory is all it has.
  RunRecord system;
  system.tracked = 7;
  system.ate_rmse = 0.02;
  std::vector<slam::StampedFrameState> plain = states;
  for (auto& f : plain) f.map = -1;
  add_atlas_accuracy(truth, atlas, plain, system);
  EXPECT_EQ(system.posed, 7);
  EXPECT_EQ(system.maps, 1);
  EXPECT_DOUBLE_EQ(system.ate_all_maps_rmse, 0.02);
}

}  // namespace
}  // namespace depot::harness
