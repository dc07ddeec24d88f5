#include "sim/sensor/depth_artefacts.h"

#include <gtest/gtest.h>

namespace depot::sim {
namespace {

// A near box (1 m) on a far wall (3 m), its colour black on the left half
// of the image and mid-grey on the right.
struct Scene {
  cv::Mat depth = cv::Mat(60, 80, CV_32F, cv::Scalar(3.0));
  cv::Mat bgr = cv::Mat(60, 80, CV_8UC3, cv::Scalar::all(128));
  Scene() {
    depth(cv::Rect(20, 20, 40, 20)).setTo(1.0);
    bgr(cv::Rect(0, 0, 40, 60)).setTo(cv::Scalar::all(0));
  }
};

TEST(DepthArtefacts, NoneSetLeavesTheDepthExact) {
  Scene s;
  const cv::Mat before = s.depth.clone();
  apply_depth_artefacts(s.depth, s.bgr, SensorSpec{}, 1);
  EXPECT_EQ(cv::norm(before, s.depth, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(before, misregister_depth(before, SensorSpec{}), cv::NORM_INF), 0.0);
}

TEST(DepthArtefacts, FlyingPixelsLieBetweenTheSurfacesAtEdgesOnly) {
  Scene s;
  SensorSpec sensor;
  sensor.flying_pixels = 1.0;
  const cv::Mat exact = s.depth.clone();
  apply_depth_artefacts(s.depth, s.bgr, sensor, 7);
  int flying = 0;
  for (int y = 0; y < exact.rows; ++y)
    for (int x = 0; x < exact.cols; ++x) {
      const float was = exact.at<float>(y, x), now = s.depth.at<float>(y, x);
      if (was == now) continue;
      ++flying;
      EXPECT_GT(now, 1.0f);
      EXPECT_LT(now, 3.0f);
      // Beside the box's outline: within one pixel of it.
      const bool inside_band = x >= 19 && x <= 60 && y >= 19 && y <= 40;
      const bool deep_inside = x >= 21 && x <= 58 && y >= 21 && y <= 38;
      EXPECT_TRUE(inside_band && !deep_inside) << x << "," << y;
    }
  // Both sides of the outline (2 x (40 + 20) x 2 pixels, less the corners).
  EXPECT_GT(flying, 200);
  SensorSpec some = sensor;
  some.flying_pixels = 0.3;
  Scene t;
  apply_depth_artefacts(t.depth, t.bgr, some, 7);
  const int fewer = cv::countNonZero(t.depth != exact);
  EXPECT_NEAR(fewer, 0.3 * flying, 0.1 * flying);
}

TEST(DepthArtefacts, DarkSurfacesLoseTheirDepth) {
  Scene s;
  SensorSpec sensor;
  sensor.dark_dropout = 1.0;
  apply_depth_artefacts(s.depth, s.bgr, sensor, 3);
  EXPECT_EQ(cv::countNonZero(s.depth(cv::Rect(0, 0, 40, 60))), 0);  // black: no IR back
  EXPECT_EQ(cv::countNonZero(s.depth(cv::Rect(40, 0, 40, 60))), 40 * 60);
}

TEST(DepthArtefacts, MisregistrationShiftsTheDepthImageByWholePixels) {
  Scene s;
  SensorSpec sensor;
  sensor.misregistration = {3.0, -2.0};
  const cv::Mat moved = misregister_depth(s.depth, sensor);
  for (int y = 0; y < 58; ++y)
    for (int x = 3; x < 80; ++x)
      ASSERT_EQ(moved.at<float>(y, x), s.depth.at<float>(y + 2, x - 3)) << x << "," << y;
  EXPECT_EQ(cv::countNonZero(moved.colRange(0, 3)), 0);
  EXPECT_EQ(cv::countNonZero(moved.rowRange(58, 60)), 0);
}

}  // namespace
}  // namespace depot::sim
