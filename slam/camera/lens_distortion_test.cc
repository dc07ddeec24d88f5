#include "slam/camera/lens_distortion.h"

#include <cmath>

#include <gtest/gtest.h>

#include "common/error.h"

namespace depot::slam {
namespace {

PinholeCamera kinect_like() {
  PinholeCamera c;
  c.fx = 535.4;
  c.fy = 539.2;
  c.lens.k1 = -0.26;
  c.lens.k2 = 0.09;
  c.lens.p1 = 0.001;
  c.lens.p2 = -0.0006;
  c.lens.k3 = -0.01;
  return c;
}

TEST(LensDistortion, UndistortingThenDistortingGivesThePixelBack) {
  const PinholeCamera c = kinect_like();
  std::vector<cv::Point2f> pixels;
  for (int v = 0; v <= 480; v += 40)
    for (int u = 0; u <= 640; u += 40) pixels.emplace_back(u, v);
  const std::vector<cv::Point2f> undistorted = undistort_pixels(c, pixels);
  ASSERT_EQ(undistorted.size(), pixels.size());
  for (size_t i = 0; i < pixels.size(); ++i) {
    const cv::Point2f back = distort_pixel(c, undistorted[i]);
    EXPECT_NEAR(back.x, pixels[i].x, 1e-3) << i;
    EXPECT_NEAR(back.y, pixels[i].y, 1e-3) << i;
  }
  // Barrel: the corner moves outwards, the centre stays.
  EXPECT_LT(undistorted.front().x, -1.0f);
  EXPECT_LT(undistorted.front().y, -1.0f);
}

TEST(LensDistortion, BoundsCoverTheUndistortedImage) {
  PinholeCamera c = kinect_like();
  set_undistorted_bounds(c, "calibration.yaml");
  EXPECT_LT(c.min_u, -5);
  EXPECT_GT(c.max_u, 645);
  EXPECT_LT(c.min_v, -5);
  EXPECT_GT(c.max_v, 485);
  EXPECT_TRUE(c.in_image(-3, 240));
  EXPECT_FALSE(c.in_image(c.max_u + 1, 240));
  PinholeCamera plain;
  set_undistorted_bounds(plain, "calibration.yaml");
  EXPECT_FALSE(plain.in_image(-3, 240));
  EXPECT_TRUE(plain.in_image(0, 0));
  EXPECT_EQ(undistort_pixels(plain, {{1.5f, 2.5f}})[0], cv::Point2f(1.5f, 2.5f));
}

TEST(LensDistortion, AFoldingLensIsOneErrorNamingTheFile) {
  PinholeCamera c;
  c.lens.k1 = -1.0;  // r (1 - r^2) never reaches the corners
  try {
    set_undistorted_bounds(c, "calibration.yaml");
    FAIL() << "a folding lens was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("calibration.yaml: the lens distortion"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace depot::slam
