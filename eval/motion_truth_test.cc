// The truth of which keypoints move, on a one-frame dataset written here: a
// moving square; the boundary rule (FAST circle at the keypoint's level) and
// precision with boundary points counted as static and left out.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/png_codec.h"
#include "eval/motion_truth.h"
#include "eval/test_files.h"

namespace depot::eval {
namespace {

std::string one_frame_dataset() {
  const std::string labels_txt =
      testing::write_test_file("labels.txt", "# timestamp filename\n1.000000 labels/1.png\n");
  const std::filesystem::path dir = std::filesystem::path(labels_txt).parent_path();
  testing::write_test_file("object_poses.txt",
                           "# timestamp id tx ty tz qx qy qz qw moving\n"
                           "1.000000 5 0 0 0 0 0 0 1 1\n"
                           "1.000000 6 0 0 0 0 0 0 1 0\n");
  cv::Mat labels(120, 160, CV_16U, cv::Scalar(1));
  labels(cv::Rect(50, 30, 40, 60)).setTo(5);   // moving: x 50..89
  labels(cv::Rect(120, 30, 20, 20)).setTo(6);  // a still object
  std::filesystem::create_directories(dir / "labels");
  const std::vector<unsigned char> png = encode_png(labels, PngKind::kLabels);
  std::ofstream((dir / "labels/1.png").string(), std::ios::binary)
      .write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
  return dir.string();
}

cv::KeyPoint at(float x, float y, int octave = 0) {
  cv::KeyPoint k(x, y, 7);
  k.octave = octave;
  return k;
}

TEST(MotionTruth, BoundaryClassFollowsTheFastCircleRule) {
  const MotionTruth truth(one_frame_dataset());
  const std::vector<cv::KeyPoint> kps = {
      at(70, 60),     // on the mover
      at(89, 60),     // on its last column
      at(92, 60),     // 3 px right of it: circle reaches -> boundary
      at(94, 60),     // 5 px at level 0 -> static
      at(94, 60, 3),  // 5 px at level 3 (radius 5.2) -> boundary
      at(130, 40),    // on the still object -> static
      at(10, 10)};    // background
  const MotionTruth::KeypointTruth t = truth.classify_keypoints(1.0, kps, 1.2f);
  EXPECT_EQ(t.on_moving, (std::vector<uint8_t>{1, 1, 0, 0, 0, 0, 0}));
  EXPECT_EQ(t.boundary, (std::vector<uint8_t>{0, 0, 1, 0, 1, 0, 0}));
  EXPECT_EQ(t.instance, (std::vector<uint16_t>{5, 5, 1, 1, 1, 6, 1}));
}

TEST(RejectionScore, PrecisionWithAndWithoutBoundaryPoints) {
  RejectionScore s;
  // Rejected: 2 moving, 1 boundary, 1 static; kept: 1 moving, 1 boundary, 2 static.
  s.add({0, 0, 0, 0, 1, 1, 1, 1}, {1, 1, 0, 0, 1, 0, 0, 0}, {0, 0, 1, 0, 0, 1, 0, 0});
  EXPECT_EQ(s.boundary_false_positive, 1);
  EXPECT_EQ(s.boundary_true_negative, 1);
  EXPECT_DOUBLE_EQ(s.precision(), 2.0 / 4.0);                   // boundary counted as static
  EXPECT_DOUBLE_EQ(s.precision_without_boundary(), 2.0 / 3.0);  // left out
  EXPECT_DOUBLE_EQ(s.recall(), 2.0 / 3.0);                      // the same both ways
}

}  // namespace
}  // namespace depot::eval
