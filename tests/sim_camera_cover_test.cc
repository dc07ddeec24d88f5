// A camera cover in a rendered dataset: covered frames are black with no
// depth and no instances, the frames around them are ordinary, the camera
// keeps moving under the cover, and the dataset stays byte-identical.
#include <algorithm>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "dataset/boxes.h"
#include "dataset/dataset_files.h"
#include "dataset/dataset_info.h"
#include "tests/support/dataset_reader.h"
#include "tests/support/render_helpers.h"

namespace depot::test {
namespace {

// People walking close to the camera (so frames have boxes to lose), with
// about three frames of its real fr3 timestamps (~30 Hz) covered. Kinect
// model on: a covered frame must not get sensor noise. Primitive actors:
// quicker, and the cover is the same.
const double kCoverStart = 0.09, kCoverEnd = 0.19;

SmallRender covered_walking() {
  SmallRender r("depot_walking_xyz", 10, 64, false);
  r.set = {{"camera_cover", "[[0.09, 0.19]]"}, {"style", "primitive"}};
  return r;
}

bool is_covered_frame(const Dataset& d, size_t i) {
  return cv::countNonZero(d.rgb(i).reshape(1)) == 0 && cv::countNonZero(d.depth_metres(i)) == 0 &&
         cv::countNonZero(d.labels_image(i)) == 0;
}

TEST(CameraCover, CoveredFramesAreBlackWithoutDepthOrInstances) {
  const Dataset d = read_dataset(render_small(covered_walking()));
  ASSERT_EQ(d.frames.size(), 10u);
  // Which frames the interval covers, from the written timestamps.
  std::vector<bool> expected;
  for (const auto& f : d.frames) {
    const double t = f.rgb_timestamp - d.frames.front().rgb_timestamp;
    expected.push_back(t >= kCoverStart && t < kCoverEnd);
  }
  const size_t first = std::find(expected.begin(), expected.end(), true) - expected.begin();
  const size_t last = first + std::count(expected.begin(), expected.end(), true) - 1;
  ASSERT_GE(first, 2u) << "uncovered frames before the cover";
  ASSERT_GE(last, first + 1) << "the cover spans frames";
  ASSERT_LE(last + 3, d.frames.size()) << "uncovered frames after the cover";
  for (size_t i = 0; i < d.frames.size(); ++i) {
    const bool covered = expected[i];
    EXPECT_EQ(is_covered_frame(d, i), covered) << "frame " << i;
    if (covered) continue;
    // An uncovered frame sees the depot: colour, valid depth, labelled things.
    EXPECT_GT(cv::countNonZero(d.rgb(i).reshape(1)), 0) << "frame " << i;
    EXPECT_GT(cv::countNonZero(d.depth_metres(i)), 0) << "frame " << i;
    EXPECT_GT(cv::countNonZero(d.labels_image(i)), 0) << "frame " << i;
  }
  // The robot drives on under the cover: the ground truth keeps moving.
  for (size_t i = first; i <= last + 1; ++i)
    EXPECT_GT(
        (d.groundtruth[i].pose.translation() - d.groundtruth[i - 1].pose.translation()).norm(),
        1e-4)
        << "frame " << i;
  // No boxes in covered frames.
  const std::vector<dataset::BoxRecord> boxes = dataset::read_boxes(d.root);
  for (const dataset::BoxRecord& b : boxes)
    for (size_t i = first; i <= last; ++i)
      EXPECT_NE(dataset::format_timestamp(b.timestamp),
                dataset::format_timestamp(d.frames[i].rgb_timestamp))
          << dataset::format_box(b);
  EXPECT_FALSE(boxes.empty())
      << "the uncovered frames do have boxes (else the check above is empty)";
  const std::optional<dataset::DatasetInfo> info = dataset::read_info(d.root);
  ASSERT_TRUE(info);
  EXPECT_EQ(
      info->covered_frames,
      (std::vector<std::pair<long, long>>{{static_cast<long>(first), static_cast<long>(last)}}));
  EXPECT_EQ(info->camera_cover, (std::vector<std::pair<double, double>>{{0.09, 0.19}}));
}

TEST(CameraCover, SameScenarioAndSeedGiveTheSameBytes) {
  const std::string a = render_small(covered_walking());
  const std::string b = render_small(covered_walking());
  EXPECT_EQ(compare_trees(a, b), "");
}

}  // namespace
}  // namespace depot::test
