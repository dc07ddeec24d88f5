#include "sim/sensor/lens.h"

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>

#include "common/error.h"
#include "common/image_size.h"

namespace depot::sim {
namespace {

// A Kinect-like barrel lens with a little decentring.
LensDistortion kinect_like() {
  return {-0.26, 0.09, 0.001, -0.0006, -0.01};
}

CameraIntrinsics vga() {
  return CameraIntrinsics{};
}

// OpenCV's own projection of the ray (x, y, 1), an independent implementation.
cv::Point2d opencv_project(const CameraIntrinsics& c, const LensDistortion& l, double x, double y) {
  const std::vector<cv::Point3d> object{{x, y, 1.0}};
  std::vector<cv::Point2d> image;
  const cv::Matx33d k(c.f, 0, c.cx, 0, c.focal_y(), c.cy, 0, 0, 1);
  const std::vector<double> dist{l.k1, l.k2, l.p1, l.p2, l.k3};
  cv::projectPoints(object, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), k, dist, image);
  return image[0];
}

TEST(Lens, DistortionIsOpenCvsAndUndistortionInvertsIt) {
  const LensDistortion l = kinect_like();
  const CameraIntrinsics c = vga();
  for (double x = -0.7; x <= 0.7; x += 0.1)
    for (double y = -0.55; y <= 0.55; y += 0.1) {
      const Eigen::Vector2d d = distort_normalised(l, {x, y});
      const cv::Point2d p = opencv_project(c, l, x, y);
      EXPECT_NEAR(c.f * d.x() + c.cx, p.x, 1e-9);
      EXPECT_NEAR(c.f * d.y() + c.cy, p.y, 1e-9);
      Eigen::Vector2d back;
      ASSERT_TRUE(undistort_normalised(l, d, back));
      EXPECT_NEAR(back.x(), x, 1e-11);
      EXPECT_NEAR(back.y(), y, 1e-11);
    }
}

TEST(Lens, EachOutputPixelShowsTheCanvasAtTheRayThatDistortsOntoIt) {
  CameraIntrinsics c = vga();
  c.fy = 545.0;  // non-square pixels too
  const LensDistortion l = kinect_like();
  ASSERT_TRUE(lens_resamples(c, l));
  const LensMapping m = make_lens_mapping(c, l, "test");
  EXPECT_EQ(m.canvas.f, 545.0);
  EXPECT_EQ(m.canvas.focal_y(), 545.0);
  // Barrel distortion: the corners' rays lie outside the undistorted frame.
  EXPECT_GT(m.canvas.width, c.width);
  EXPECT_GT(m.canvas.height, c.height);
  EXPECT_LE(m.canvas.width, kMaxImageSide);
  double worst = 0;
  for (int v = 0; v < c.height; v += 7)
    for (int u = 0; u < c.width; u += 7) {
      const double x = (m.map_x.at<float>(v, u) - m.canvas.cx) / m.canvas.f;
      const double y = (m.map_y.at<float>(v, u) - m.canvas.cy) / m.canvas.f;
      const cv::Point2d p = opencv_project(c, l, x, y);
      worst = std::max(worst, std::hypot(p.x - u, p.y - v));
      EXPECT_GE(m.map_x.at<float>(v, u), 0.0f);
      EXPECT_LT(m.map_x.at<float>(v, u), m.canvas.width - 1.0f);
      EXPECT_GE(m.map_y.at<float>(v, u), 0.0f);
      EXPECT_LT(m.map_y.at<float>(v, u), m.canvas.height - 1.0f);
    }
  // Float maps hold a canvas position to about 1e-4 px.
  EXPECT_LT(worst, 2e-3);
}

TEST(Lens, APinholeWithSquarePixelsIsNotResampled) {
  EXPECT_FALSE(lens_resamples(vga(), LensDistortion{}));
  CameraIntrinsics c = vga();
  c.fy = c.f;
  EXPECT_FALSE(lens_resamples(c, LensDistortion{}));
  EXPECT_TRUE(lens_resamples(c, LensDistortion{0, 0, 0, 0, 0.01}));
}

TEST(Lens, DepthAndLabelsComeFromOneCanvasPixelColourIsInterpolated) {
  CameraIntrinsics c = vga();
  c.width = 64;
  c.height = 48;
  c.f = 54.0;
  c.cx = 32.0;
  c.cy = 24.0;
  const LensMapping m = make_lens_mapping(c, kinect_like(), "test");
  RenderedFrame canvas;
  canvas.depth.create(m.canvas.height, m.canvas.width, CV_32F);
  canvas.instance.create(m.canvas.height, m.canvas.width, CV_16U);
  canvas.bgr.create(m.canvas.height, m.canvas.width, CV_8UC3);
  for (int y = 0; y < m.canvas.height; ++y)
    for (int x = 0; x < m.canvas.width; ++x) {
      canvas.depth.at<float>(y, x) = 1.0f + 0.01f * x + 0.5f * y;
      canvas.instance.at<uint16_t>(y, x) = static_cast<uint16_t>(1000 * y + x);
      canvas.bgr.at<cv::Vec3b>(y, x) = cv::Vec3b(static_cast<uint8_t>(2 * x), 0, 0);
    }
  RenderedFrame out;
  apply_lens(m, canvas, out);
  ASSERT_EQ(out.depth.size(), cv::Size(64, 48));
  for (int v = 0; v < 48; ++v)
    for (int u = 0; u < 64; ++u) {
      const int x = cvRound(m.map_x.at<float>(v, u)), y = cvRound(m.map_y.at<float>(v, u));
      ASSERT_EQ(out.instance.at<uint16_t>(v, u), 1000 * y + x) << u << "," << v;
      ASSERT_EQ(out.depth.at<float>(v, u), canvas.depth.at<float>(y, x));
      // Colour: bilinear along a ramp of 2 levels per canvas pixel.
      EXPECT_NEAR(out.bgr.at<cv::Vec3b>(v, u)[0], 2 * m.map_x.at<float>(v, u), 1.01);
    }
}

TEST(Lens, ALensThatFoldsTheImageOrNeedsAHugeCanvasIsRefused) {
  // k1 = -1: r (1 - r^2) never reaches the corners' 0.74.
  try {
    make_lens_mapping(vga(), LensDistortion{-1.0, 0, 0, 0, 0}, "s.yaml");
    FAIL() << "a folding lens was accepted";
  } catch (const Error& e) {
    EXPECT_THAT(std::string(e.what()), ::testing::HasSubstr("s.yaml: the lens distortion"))
        << e.what();
    EXPECT_THAT(std::string(e.what()), ::testing::HasSubstr("folds the image")) << e.what();
  }
  // r - 3 r^3 + 3 r^5 turns back at r 0.38 and again at 0.67, then reaches
  // the corners: three rays share some pixels.
  EXPECT_THROW(make_lens_mapping(vga(), LensDistortion{-3.0, 3.0, 0, 0, 0}, "s.yaml"), Error);
  CameraIntrinsics wide = vga();
  wide.width = 4000;
  wide.f = 1000;
  wide.cx = 2000;
  wide.fy = 4000;  // the canvas takes the finer pitch: 16000 px wide
  EXPECT_THROW(make_lens_mapping(wide, LensDistortion{}, "s.yaml"), Error);
}

}  // namespace
}  // namespace depot::sim
