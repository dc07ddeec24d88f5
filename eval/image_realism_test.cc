#include "eval/image_realism.h"

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

namespace depot::eval {
namespace {

// A smooth ramp (no texture) with Gaussian noise of `sigma` grey levels.
cv::Mat noisy_ramp(double sigma, uint64_t seed) {
  cv::Mat f(240, 320, CV_32F);
  for (int y = 0; y < f.rows; ++y)
    for (int x = 0; x < f.cols; ++x) f.at<float>(y, x) = 40.0f + 0.5f * x;
  cv::Mat noise(f.size(), CV_32F);
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::NORMAL, 0.0, sigma);
  cv::Mat grey, bgr;
  cv::Mat(f + noise).convertTo(grey, CV_8U);
  cv::cvtColor(grey, bgr, cv::COLOR_GRAY2BGR);
  return bgr;
}

TEST(ImageRealism, NoiseOfAKnownSigmaIsMeasuredInItsBrightnessBins) {
  for (double sigma : {1.5, 4.0}) {
    const Realism r = summarise_realism("x", {measure_frame(noisy_ramp(sigma, 3), {}, {})});
    int measured = 0;
    for (double s : r.noise_sigma) {
      if (std::isnan(s)) continue;
      ++measured;
      EXPECT_NEAR(s, sigma, 0.12 * sigma);
    }
    EXPECT_GE(measured, 4) << "the ramp spans grey 40-200";
    EXPECT_TRUE(std::isnan(r.noise_sigma.back())) << "nothing brighter than 224";
    EXPECT_TRUE(std::isnan(r.hole_share));
    EXPECT_TRUE(std::isnan(r.motion_median));
  }
}

TEST(ImageRealism, BlurLowersSharpnessAndMotionIsMeasured) {
  cv::Mat texture(240, 320, CV_8UC3);
  cv::RNG rng(7);
  rng.fill(texture, cv::RNG::UNIFORM, 0, 255);
  cv::GaussianBlur(texture, texture, cv::Size(0, 0), 1.2);
  cv::Mat blurred;
  cv::blur(texture, blurred, cv::Size(9, 1));
  const FrameRealism sharp = measure_frame(texture, {}, {});
  const FrameRealism soft = measure_frame(blurred, {}, {});
  EXPECT_LT(soft.sharpness, 0.5 * sharp.sharpness);
  // The same texture 3 px to the right.
  cv::Mat moved;
  const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, 3, 0, 1, 0);
  cv::warpAffine(texture, moved, shift, texture.size());
  cv::Mat grey;
  cv::cvtColor(texture, grey, cv::COLOR_BGR2GRAY);
  EXPECT_NEAR(measure_frame(moved, {}, grey).motion_px, 3.0, 0.2);
}

TEST(ImageRealism, DepthHolesAreCountedAtEdgesAndByDepth) {
  // A near box (1.5 m) on a far wall (3.5 m), a 2 px hole strip along its
  // right edge as a projector shadow leaves.
  cv::Mat depth(240, 320, CV_32F, cv::Scalar(3.5));
  depth(cv::Rect(100, 60, 100, 120)).setTo(1.5);
  depth(cv::Rect(200, 60, 2, 120)).setTo(0);
  cv::Mat bgr(depth.size(), CV_8UC3, cv::Scalar::all(128));
  const Realism r = summarise_realism("x", {measure_frame(bgr, depth, {})});
  EXPECT_NEAR(r.hole_share, 240.0 / (320 * 240), 1e-9);
  EXPECT_GT(r.edge_hole_share, 0.05);                 // the holes sit on the edge...
  EXPECT_TRUE(std::isnan(r.hole_share_by_depth[0]));  // nothing nearer than 1 m
  EXPECT_EQ(r.hole_share_by_depth[1], 0.0);           // the box's inside: no hole
  EXPECT_GT(r.hole_share_by_depth[2] + r.hole_share_by_depth[3], 0.0);
  EXPECT_TRUE(std::isnan(r.hole_share_by_depth[4]) || r.hole_share_by_depth[4] == 0.0);
}

TEST(ImageRealism, TableAndPageShowBothRecordings) {
  const Realism a = summarise_realism("sim", {measure_frame(noisy_ramp(2.0, 1), {}, {})});
  const Realism b = summarise_realism("real", {measure_frame(noisy_ramp(4.0, 2), {}, {})});
  const std::string table = format_realism_table(a, b);
  EXPECT_NE(table.find("noise sigma, grey 96-127"), std::string::npos) << table;
  EXPECT_THAT(table, ::testing::HasSubstr("sim")) << table;
  EXPECT_THAT(table, ::testing::HasSubstr("ratio")) << table;
  const std::string page = realism_page(a, b);
  EXPECT_THAT(page, ::testing::HasSubstr("<svg"));
  EXPECT_THAT(page, ::testing::HasSubstr("Noise by brightness"));
}

}  // namespace
}  // namespace depot::eval
