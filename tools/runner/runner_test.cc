// The run's observers on hand-made frames, and run_sequence's promise that a
// run that tracks nothing leaves none of its files.
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "common/error.h"
#include "common/png_codec.h"
#include "common/testing/scratch_folder.h"
#include "tests/support/room_vocabulary.h"
#include "tests/support/synthetic_room.h"
#include "tools/runner/dense_map.h"
#include "tools/runner/frame_timings.h"
#include "tools/runner/slam_runner.h"
#include "tools/runner/stats_table.h"

namespace depot::runner {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

slam::TrackResult tracked(slam::TrackingState state, double total_ms, double track_ms) {
  slam::TrackResult r;
  r.state = state;
  r.keypoints = r.kept = 500;
  r.timing.total_ms = total_ms;
  r.timing.track_ms = track_ms;
  return r;
}

// A frame of plain orb (no filter, no truth) as run_sequence records it.
FrameRecord orb_frame(size_t index, const slam::TrackResult& r, const cv::Mat& image) {
  FrameRecord record{index, 100.0 + index, image, image, r, nullptr, {}, {}, nullptr};
  record.rejection.total = record.rejection.kept = record.rejection.p = r.keypoints;
  return record;
}

TEST(StatsTable, WritesAHeaderAndARowPerFrameOnlyWhenCommitted) {
  testkit::ScratchFolder scratch("stats_table");
  const std::string path = scratch.file("stats.csv");
  const cv::Mat image(4, 4, CV_8UC3, cv::Scalar::all(0));
  {
    StatsTable table(path);
    const slam::TrackResult r = tracked(slam::TrackingState::kOk, 12.5, 4.0);
    table.on_frame(orb_frame(0, r, image));
    table.on_frame(orb_frame(1, r, image));
    EXPECT_FALSE(fs::exists(path)) << "staged until the run succeeds";
    table.commit();
  }
  std::istringstream lines(read_text(path));
  std::string header, row0, row1, extra;
  std::getline(lines, header);
  std::getline(lines, row0);
  std::getline(lines, row1);
  EXPECT_FALSE(std::getline(lines, extra));
  EXPECT_THAT(header, testing::StartsWith("frame,timestamp,state,keypoints,kept,Z,Q,Q_to_P,P,"));
  // orb: every keypoint kept and in P, nothing judged (real data: zeros).
  EXPECT_THAT(row0, testing::StartsWith("0,100.000000,OK,500,500,0,0,0,500,0,"));
  EXPECT_THAT(row1, testing::StartsWith("1,101.000000,OK,500,500,0,0,0,500,0,"));
  EXPECT_THAT(row0, HasSubstr(",12.50,0,0,0,0,0,"));
}

TEST(StatsTable, AnUncommittedTableLeavesNoFile) {
  testkit::ScratchFolder scratch("stats_table");
  const std::string path = scratch.file("stats.csv");
  { StatsTable table(path); }
  EXPECT_FALSE(fs::exists(path));
  EXPECT_TRUE(fs::is_empty(scratch.path())) << "no staging file left behind";
}

TEST(FrameTimings, MediansCountsAndTheRelocalisationTime) {
  const cv::Mat image(4, 4, CV_8UC3, cv::Scalar::all(0));
  FrameTimings timings;
  using S = slam::TrackingState;
  // Two lost frames: the frames after them are where relocalisation is tried.
  const slam::TrackResult frames[] = {tracked(S::kOk, 10, 5), tracked(S::kLost, 30, 20),
                                      tracked(S::kLost, 40, 25), tracked(S::kRelocalized, 50, 35),
                                      tracked(S::kOk, 20, 6)};
  for (size_t i = 0; i < 5; ++i) timings.on_frame(orb_frame(i, frames[i], image));
  RunSummary summary;
  timings.add_to(summary);
  EXPECT_EQ(summary.lost, 2);
  EXPECT_EQ(summary.relocalized, 1);
  EXPECT_DOUBLE_EQ(summary.median_ms, 30);  // of 10 20 30 40 50
  EXPECT_DOUBLE_EQ(summary.p95_ms, 50);
  EXPECT_DOUBLE_EQ(summary.track_ms, 20);  // of 5 6 20 25 35
  // Only the frames after a lost one count (25 and 35 ms; the median's rank
  // rounds up, common/percentile.h): not the lost frames' own 20 and 25.
  EXPECT_DOUBLE_EQ(summary.lost_ms, 35);
  EXPECT_DOUBLE_EQ(summary.filter_ms, 0) << "no filter, no rejection times";
}

TEST(DenseMapBuilder, RefusesMasksTheRunCannotMake) {
  testkit::ScratchFolder scratch("dense_map");
  const slam::PinholeCamera camera;
  const std::string ply = scratch.file("map.ply");
  try {
    DenseMapBuilder(ply, DenseMask::kLabels, {}, camera, nullptr, nullptr, "real_data", "orb");
    FAIL() << "labels without a simulated dataset";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("real_data: has no labels"));
  }
  try {
    DenseMapBuilder(ply, DenseMask::kRejection, {}, camera, nullptr, nullptr, "sim", "orb");
    FAIL() << "rejection masks without a filter";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("mode orb leaves no moving mask"));
  }
  EXPECT_NO_THROW(
      DenseMapBuilder(ply, DenseMask::kNone, {}, camera, nullptr, nullptr, "real_data", "orb"));
  EXPECT_FALSE(fs::exists(ply));
}

// A TUM folder of `frames` blank frames: nothing to track.
std::string blank_dataset(const testkit::ScratchFolder& scratch, int frames) {
  const fs::path folder = scratch.path() / "blank";
  fs::create_directories(folder / "rgb");
  fs::create_directories(folder / "depth");
  std::ofstream rgb((folder / "rgb.txt").string()), depth((folder / "depth.txt").string());
  const cv::Mat grey(480, 640, CV_8UC3, cv::Scalar::all(128));
  const cv::Mat far(480, 640, CV_16UC1, cv::Scalar(10000));  // 2 m
  for (int i = 0; i < frames; ++i) {
    const std::string name = std::to_string(i) + ".png";
    write_png((folder / "rgb" / name).string(), grey, PngKind::kColor);
    write_png((folder / "depth" / name).string(), far, PngKind::kDepth);
    rgb << 1.0 + i * 0.033 << " rgb/" << name << "\n";
    depth << 1.0 + i * 0.033 << " depth/" << name << "\n";
  }
  return folder.string();
}

TEST(RunSequence, ARunThatTracksNothingFailsAndLeavesNoneOfItsFiles) {
  testkit::ScratchFolder scratch("run_sequence");
  RunOptions options;
  options.input.dataset = blank_dataset(scratch, 3);
  options.input.vocabulary = test::room_vocabulary_file();
  options.input.sync = true;
  options.quiet = true;
  options.outputs.stats_csv = scratch.file("stats.csv");
  options.outputs.dense_map = scratch.file("cloud.ply");
  options.outputs.dense_mask = "none";
  options.map.save_map = scratch.file("run.map");
  try {
    run_sequence(options);
    FAIL() << "a blank sequence cannot be tracked";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr(std::string(kNoFrameTracked) + ": tracking never initialised"));
  }
  for (const std::string& file :
       {options.outputs.stats_csv, options.outputs.dense_map, options.map.save_map})
    EXPECT_FALSE(fs::exists(file)) << file << " of a run that posed no frame";
}

TEST(RunSequence, ChecksTheInputBeforeAnyWork) {
  testkit::ScratchFolder scratch("run_sequence");
  RunOptions options;
  options.input.dataset = blank_dataset(scratch, 2);
  options.quiet = true;
  options.input.frames = 5;
  EXPECT_THROW(
      {
        try {
          run_sequence(options);
        } catch (const Error& e) {
          EXPECT_THAT(e.what(), HasSubstr("has 2 frames; --frames asks for 5"));
          throw;
        }
      },
      Error);
  options.input.frames.reset();
  options.map.localise_only = true;
  EXPECT_THROW(run_sequence(options), Error);
  options.map.localise_only = false;
  options.outputs.keypoints_csv = scratch.file("keypoints.csv");  // orb has no keypoint sets
  try {
    run_sequence(options);
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("per-keypoint rows need a rejection mode"));
  }
  EXPECT_FALSE(fs::exists(options.outputs.keypoints_csv));
}

// A TUM folder of room views (synthetic_room.h), PNG as a recording's.
class RoomDataset {
 public:
  explicit RoomDataset(const fs::path& folder) : folder_(folder) {
    fs::create_directories(folder / "rgb");
    fs::create_directories(folder / "depth");
  }
  void add(const cv::Mat& bgr, const cv::Mat& depth_m) {
    const std::string name = std::to_string(frames_) + ".png";
    const double t = 1.0 + 0.1 * frames_++;
    cv::Mat depth;
    depth_m.convertTo(depth, CV_16U, 5000.0);  // TUM's depth scale
    write_png((folder_ / "rgb" / name).string(), bgr, PngKind::kColor);
    write_png((folder_ / "depth" / name).string(), depth, PngKind::kDepth);
    rgb_ << std::fixed << t << " rgb/" << name << "\n";
    depth_ << std::fixed << t << " depth/" << name << "\n";
  }
  std::string finish() {
    std::ofstream((folder_ / "rgb.txt").string()) << rgb_.str();
    std::ofstream((folder_ / "depth.txt").string()) << depth_.str();
    return folder_.string();
  }

 private:
  fs::path folder_;
  int frames_ = 0;
  std::ostringstream rgb_, depth_;
};

// Each map of the atlas gets its own dense map: the camera is covered and
// then sees a place the first map never saw (the room mirrored), so a
// second map starts there and is never merged; its cloud lies in its own
// frame, beside the main map's file.
TEST(DenseMapBuilder, EveryMapOfTheAtlasGetsItsOwnDenseMap) {
  testkit::ScratchFolder scratch("dense_atlas");
  RoomDataset dataset(scratch.path() / "room");
  for (double yaw : {0.0, 2.0, 4.0, 6.0, 8.0}) {
    const test::RealFrame v = test::room_view(test::turn(yaw));
    dataset.add(v.bgr, v.depth);
  }
  const test::RealFrame first = test::room_view(test::turn(0));
  dataset.add(cv::Mat(first.bgr.size(), CV_8UC3, cv::Scalar::all(90)),
              cv::Mat(first.depth.size(), CV_32F, cv::Scalar(0)));
  for (double yaw : {0.0, 2.0, 4.0}) {
    const test::RealFrame v = test::room_view(test::turn(yaw));
    cv::Mat bgr, depth;
    cv::flip(v.bgr, bgr, 1);
    cv::flip(v.depth, depth, 1);
    dataset.add(bgr, depth);
  }
  RunOptions options;
  options.input.dataset = dataset.finish();
  options.input.vocabulary = test::room_vocabulary_file();
  // Keep the young maps (ORB-SLAM2 resets a lost map of <= 5 keyframes).
  options.input.settings =
      scratch.write("settings.yaml", "tracking: {reset_keyframes: 0, atlas: true}\n");
  options.input.sync = true;
  options.quiet = true;
  options.outputs.dense_map = scratch.file("room.ply");
  options.outputs.dense_mask = "none";
  options.outputs.dense.min_views = 1;
  const RunSummary s = run_sequence(options);
  EXPECT_EQ(s.maps, 2);
  ASSERT_EQ(s.dense_other_maps.size(), 1u);
  const RunSummary::DenseMapFile& other = s.dense_other_maps[0];
  EXPECT_EQ(other.map, 1);
  EXPECT_EQ(other.path, scratch.file("room.map1.ply")) << other.reason;
  EXPECT_GT(other.points, 1000u);
  EXPECT_GE(other.keyframes, 1);
  EXPECT_GT(s.dense_points, 1000u);
  EXPECT_TRUE(fs::exists(options.outputs.dense_map));
  EXPECT_TRUE(fs::exists(other.path));
  EXPECT_EQ(dense_map_path("out/d.ply", 2), "out/d.map2.ply");
  EXPECT_EQ(dense_map_path("d.ply", 0), "d.ply");
}

}  // namespace
}  // namespace depot::runner
