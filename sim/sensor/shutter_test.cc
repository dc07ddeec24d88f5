#include "sim/sensor/shutter.h"

#include <cmath>

#include <gtest/gtest.h>

namespace depot::sim {
namespace {

TEST(Shutter, SubFramesSpanTheExposureAndReadoutWithTheTimestampInTheMiddle) {
  ShutterTiming t{0.02, 0.01, 15};
  const auto o = subframe_offsets(t, 6.2);  // 6.2 px of motion: 8 wanted, 9 (odd)
  ASSERT_EQ(o.size(), 9u);
  EXPECT_DOUBLE_EQ(o.front(), -0.015);
  EXPECT_DOUBLE_EQ(o.back(), 0.015);
  EXPECT_EQ(o[4], 0.0);
  for (size_t i = 1; i < o.size(); ++i) EXPECT_GT(o[i], o[i - 1]);
  EXPECT_EQ(subframe_offsets(t, 0.0).size(), 3u);                             // at least 3
  EXPECT_EQ(subframe_offsets(t, 500.0).size(), 15u);                          // capped
  EXPECT_EQ(subframe_offsets(ShutterTiming{0.02, 0, 10}, 500.0).size(), 9u);  // odd cap
  EXPECT_EQ(subframe_offsets(ShutterTiming{}, 100.0), std::vector<double>{0.0});
}

TEST(Shutter, RowsRunFromHalfTheReadoutBeforeToHalfAfter) {
  ShutterTiming t{0.0, 0.03, 15};
  EXPECT_DOUBLE_EQ(t.row_offset(0, 480), -0.015);
  EXPECT_DOUBLE_EQ(t.row_offset(479, 480), 0.015);
  EXPECT_NEAR(t.row_offset(240, 480), 0.0, 0.03 / 479);
}

// Sub-frames of one bright column moving one pixel per sub-frame.
std::vector<cv::Mat> moving_column(int count, int rows) {
  std::vector<cv::Mat> frames;
  for (int k = 0; k < count; ++k) {
    cv::Mat f(rows, 32, CV_8UC3, cv::Scalar::all(0));
    f.col(8 + k).setTo(cv::Scalar::all(240));
    frames.push_back(f);
  }
  return frames;
}

TEST(Shutter, ExposureAveragesTheSubFramesOverTheWindow) {
  ShutterTiming t{0.02, 0.0, 15};
  const auto offsets = subframe_offsets(t, 4.0);  // 5 sub-frames, 5 ms apart
  ASSERT_EQ(offsets.size(), 5u);
  const cv::Mat out = integrate_shutter(moving_column(5, 4), offsets, t);
  // Linear interpolation in time: the end columns get half the weight of
  // the inner ones (1/8 vs 1/4 of the window), and the light is conserved.
  EXPECT_EQ(out.at<cv::Vec3b>(0, 8)[0], 30);
  EXPECT_EQ(out.at<cv::Vec3b>(0, 10)[0], 60);
  EXPECT_EQ(out.at<cv::Vec3b>(0, 12)[0], 30);
  EXPECT_EQ(out.at<cv::Vec3b>(0, 13)[0], 0);
  EXPECT_EQ(cv::sum(out.row(0))[0], 240.0);
}

TEST(Shutter, ReadoutGivesEachRowItsOwnInstant) {
  ShutterTiming t{0.0, 0.04, 15};
  const auto offsets = subframe_offsets(t, 4.0);  // 5 sub-frames, 10 ms apart
  const cv::Mat out = integrate_shutter(moving_column(5, 5), offsets, t);
  // Row y is at -20 + 10 y ms: exactly sub-frame y.
  for (int y = 0; y < 5; ++y) {
    EXPECT_EQ(out.at<cv::Vec3b>(y, 8 + y)[1], 240) << y;
    EXPECT_EQ(cv::sum(out.row(y))[1], 240.0) << y;
  }
}

TEST(Shutter, CameraMotionOfAPureTurnIsFocalTimesTheAngleAtTheCentre) {
  const double angle = 0.01;
  const Pose a = Pose::Identity();
  Pose b = Pose::Identity();
  b.linear() = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitY()).toRotationMatrix();
  // 101 x 101 image, principal point in the middle: the centre moves by
  // f tan(angle), the corners more.
  const double most = camera_image_motion(a, b, 500.0, 50.0, 50.0, 101, 101, 2.0);
  EXPECT_GT(most, 500.0 * std::tan(angle));
  EXPECT_LT(most, 1.05 * 500.0 * std::tan(angle));
  EXPECT_EQ(camera_image_motion(a, a, 500.0, 50.0, 50.0, 101, 101, 2.0), 0.0);
}

}  // namespace
}  // namespace depot::sim
