#include "sim/sensor/motion_field.h"

#include <cmath>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

namespace depot::sim {
namespace {

CameraIntrinsics small_camera() {
  CameraIntrinsics c;
  c.width = 160;
  c.height = 120;
  c.f = 140.0;
  c.cx = 79.5;
  c.cy = 59.5;
  return c;
}

// A smooth colour texture (sums of sines).
cv::Mat texture(const CameraIntrinsics& c) {
  cv::Mat image(c.height, c.width, CV_8UC3);
  for (int y = 0; y < c.height; ++y)
    for (int x = 0; x < c.width; ++x) {
      auto& p = image.at<cv::Vec3b>(y, x);
      p[0] = static_cast<uchar>(128 + 90 * std::sin(0.21 * x) * std::cos(0.13 * y));
      p[1] = static_cast<uchar>(128 + 90 * std::sin(0.09 * x + 0.17 * y));
      p[2] = static_cast<uchar>(128 + 90 * std::cos(0.15 * x - 0.05 * y));
    }
  return image;
}

Pose translated(double x, double y, double z) {
  Pose p = Pose::Identity();
  p.translation() = Eigen::Vector3d(x, y, z);
  return p;
}

TEST(MotionField, AStillWorldGivesTheRenderItself) {
  const CameraIntrinsics c = small_camera();
  const cv::Mat bgr = texture(c);
  const cv::Mat depth(c.height, c.width, CV_32F, cv::Scalar(2.0f));
  const cv::Mat body(c.height, c.width, CV_16S, cv::Scalar(-1));
  cv::Mat out;
  synthesise_subframe(make_field_source(bgr, depth, body, c), InstantMotion{}, out);
  EXPECT_EQ(cv::norm(out, bgr, cv::NORM_INF), 0.0);
}

TEST(MotionField, ACameraMovingSidewaysShiftsAPlaneByFocalTimesStepOverDepth) {
  const CameraIntrinsics c = small_camera();
  const cv::Mat bgr = texture(c);
  // 4 px at f = 140: points land on whole pixels, as a render's edges do.
  const double depth_m = 2.0, step = 4.0 * depth_m / 140.0;
  const cv::Mat depth(c.height, c.width, CV_32F, cv::Scalar(depth_m));
  const cv::Mat body(c.height, c.width, CV_16S, cv::Scalar(-1));
  // The camera moves +x: the scene moves -x in the image.
  const InstantMotion m =
      instant_motion(Pose::Identity(), {}, translated(step, 0, 0), std::vector<Pose>{});
  cv::Mat out;
  synthesise_subframe(make_field_source(bgr, depth, body, c), m, out);
  const double shift = c.f * step / depth_m;
  // The exact image: each pixel shows what was `shift` to its right.
  cv::Mat map_x(c.height, c.width, CV_32F), map_y(c.height, c.width, CV_32F);
  for (int y = 0; y < c.height; ++y)
    for (int x = 0; x < c.width; ++x) {
      map_x.at<float>(y, x) = static_cast<float>(x + shift);
      map_y.at<float>(y, x) = static_cast<float>(y);
    }
  cv::Mat expected;
  cv::remap(bgr, expected, map_x, map_y, cv::INTER_LINEAR);
  const cv::Rect inside(2, 2, c.width - 8, c.height - 4);
  cv::Mat difference;
  cv::absdiff(out(inside), expected(inside), difference);
  const double mean = cv::mean(difference.reshape(1))[0];
  std::printf("plane shifted %.2f px: mean error %.3f grey levels\n", shift, mean);
  EXPECT_LT(mean, 0.01);
  // Not the unmoved image (the comparison can tell a shift apart).
  cv::absdiff(bgr(inside), expected(inside), difference);
  EXPECT_GT(cv::mean(difference.reshape(1))[0], 10.0);
  // Content entering at the right border (the last 4 columns, reached by no
  // point) takes the colour of the last column reached.
  const cv::Vec3b last_reached = out.at<cv::Vec3b>(60, c.width - 5);
  EXPECT_NE(last_reached, cv::Vec3b(0, 0, 0));
  for (int x = c.width - 4; x < c.width; ++x) EXPECT_EQ(out.at<cv::Vec3b>(60, x), last_reached);
}

TEST(MotionField, ABandEnteringAtTheBottomTakesTheLastRowReachedAsFarAsTheFillReaches) {
  const CameraIntrinsics c = small_camera();
  const cv::Mat bgr = texture(c);
  // The camera moves +y by 100 px at this depth: the bottom 100 rows are
  // reached by no point, whole rows, so only the pixels above can fill them.
  const double depth_m = 2.0, shift = 100.0, step = shift * depth_m / c.f;
  const cv::Mat depth(c.height, c.width, CV_32F, cv::Scalar(depth_m));
  const cv::Mat body(c.height, c.width, CV_16S, cv::Scalar(-1));
  const InstantMotion m =
      instant_motion(Pose::Identity(), {}, translated(0, step, 0), std::vector<Pose>{});
  cv::Mat out;
  synthesise_subframe(make_field_source(bgr, depth, body, c), m, out);
  const int last_reached = c.height - 1 - static_cast<int>(shift);
  for (int x : {0, 37, c.width - 1}) {
    const cv::Vec3b colour = out.at<cv::Vec3b>(last_reached, x);
    EXPECT_EQ(colour, bgr.at<cv::Vec3b>(c.height - 1, x)) << "column " << x;
    // 96 rows below it take its colour; farther stays black.
    for (int y = last_reached + 1; y <= last_reached + 96; ++y)
      ASSERT_EQ(out.at<cv::Vec3b>(y, x), colour) << "row " << y << ", column " << x;
    for (int y = last_reached + 97; y < c.height; ++y)
      ASSERT_EQ(out.at<cv::Vec3b>(y, x), cv::Vec3b(0, 0, 0)) << "row " << y << ", column " << x;
  }
}

TEST(MotionField, ANearerBodyCoversWhatIsBehindAndUncoversTheBackground) {
  const CameraIntrinsics c = small_camera();
  cv::Mat bgr(c.height, c.width, CV_8UC3, cv::Scalar(40, 80, 120));
  cv::Mat depth(c.height, c.width, CV_32F, cv::Scalar(4.0f));
  cv::Mat instance(c.height, c.width, CV_16U, cv::Scalar(0));
  const cv::Rect square(50, 40, 30, 30);
  bgr(square).setTo(cv::Scalar(250, 250, 250));
  depth(square).setTo(1.0f);
  instance(square).setTo(5);
  // One body of instance 5, 1 m ahead, moving 0.1 m right: 14 px.
  const Pose body_at_stamp = translated(0.0, 0.0, 1.0);
  const cv::Mat body = assign_bodies(depth, instance, c, {5}, {body_at_stamp.translation()});
  EXPECT_EQ(body.at<int16_t>(55, 65), 0);
  EXPECT_EQ(body.at<int16_t>(10, 10), -1);
  const InstantMotion m = instant_motion(Pose::Identity(), {body_at_stamp}, Pose::Identity(),
                                         {translated(0.1, 0.0, 1.0)});
  cv::Mat out;
  synthesise_subframe(make_field_source(bgr, depth, body, c), m, out);
  // Moved square, and the background it uncovered.
  EXPECT_EQ(out.at<cv::Vec3b>(55, 50 + 14 + 20), cv::Vec3b(250, 250, 250));
  EXPECT_EQ(out.at<cv::Vec3b>(55, 50 + 29 + 14), cv::Vec3b(250, 250, 250));
  EXPECT_EQ(out.at<cv::Vec3b>(55, 52), cv::Vec3b(40, 80, 120));
  EXPECT_EQ(out.at<cv::Vec3b>(55, 50 + 12), cv::Vec3b(40, 80, 120));
  // The static scene behind stays where it was.
  EXPECT_EQ(out.at<cv::Vec3b>(55, 100), cv::Vec3b(40, 80, 120));
  EXPECT_EQ(out.at<cv::Vec3b>(20, 65), cv::Vec3b(40, 80, 120));
}

TEST(MotionField, EachPixelFollowsTheNearestBodyOfItsOwnInstance) {
  const CameraIntrinsics c = small_camera();
  const cv::Mat depth(c.height, c.width, CV_32F, cv::Scalar(2.0f));
  cv::Mat instance(c.height, c.width, CV_16U, cv::Scalar(3));
  instance(cv::Rect(0, 0, c.width, 10)).setTo(0);  // the static scene
  // Bodies 0 and 2 belong to instance 3, left and right of the centre;
  // body 1 (instance 4) is nearer the left half but not of its instance.
  const std::vector<uint16_t> owner = {3, 4, 3};
  const std::vector<Eigen::Vector3d> origin = {{-0.5, 0.0, 2.0}, {-0.3, 0.0, 2.0}, {0.5, 0.0, 2.0}};
  const cv::Mat body = assign_bodies(depth, instance, c, owner, origin);
  EXPECT_EQ(body.at<int16_t>(60, 20), 0);
  // At x = 58 (X = -0.31 m) body 1 is the nearest of all, but not of this
  // pixel's instance.
  EXPECT_EQ(body.at<int16_t>(60, 58), 0);
  EXPECT_EQ(body.at<int16_t>(60, 140), 2);
  EXPECT_EQ(body.at<int16_t>(5, 20), -1);
}

}  // namespace
}  // namespace depot::sim
