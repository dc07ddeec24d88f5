#include "sim/sensor/colour_pipeline.h"

#include <cmath>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "sim/sensor/auto_exposure.h"
#include "sim/sensor/kinect_model.h"

namespace depot::sim {
namespace {

// A sensor whose pipeline runs with nothing switched on but `change`.
SensorSpec pipeline_sensor() {
  SensorSpec s;
  s.rgb_noise = 0;
  s.light.events = {{0.0, 1.0}};  // constant at 1, but the pipeline runs
  return s;
}

double linear(uint8_t v) {
  return srgb_decode(v / 255.0);
}

cv::Mat flat(int value, int width = 64, int height = 48) {
  return cv::Mat(height, width, CV_8UC3, cv::Scalar(value, value, value));
}

TEST(ColourPipeline, OffLeavesTheRenderPlusItsOldNoise) {
  SensorSpec s;
  ASSERT_FALSE(s.forms_colour());
  cv::Mat a = flat(100), b = flat(100);
  apply_colour_sensor(a, s, {}, 7);
  apply_rgb_noise(b, s.rgb_noise, 7);
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
}

TEST(ColourPipeline, AtTheReferenceEveryGreyLevelComesBackExactly) {
  const SensorSpec s = pipeline_sensor();
  ASSERT_TRUE(s.forms_colour());
  cv::Mat ramp(1, 256, CV_8UC3);
  for (int i = 0; i < 256; ++i) ramp.at<cv::Vec3b>(0, i) = cv::Vec3b(i, i, i);
  cv::Mat out = ramp.clone();
  apply_colour_sensor(out, s, {}, 1);
  EXPECT_EQ(cv::norm(out, ramp, cv::NORM_INF), 0.0);
}

TEST(ColourPipeline, LightAndExposureScaleLinearLight) {
  const SensorSpec s = pipeline_sensor();
  ColourCapture half;
  half.row_light.assign(48, 0.5f);
  ColourCapture double_exposure;
  double_exposure.scale = 2.0;
  for (int v : {40, 120, 200}) {
    cv::Mat dim = flat(v), bright = flat(v);
    apply_colour_sensor(dim, s, half, 1);
    apply_colour_sensor(bright, s, double_exposure, 1);
    EXPECT_NEAR(dim.at<cv::Vec3b>(10, 10)[1], 255 * srgb_encode(0.5 * linear(v)), 0.6) << v;
    EXPECT_NEAR(bright.at<cv::Vec3b>(10, 10)[1], 255 * srgb_encode(std::min(1.0, 2 * linear(v))),
                0.6)
        << v;
  }
  cv::Mat white = flat(250);
  apply_colour_sensor(white, s, double_exposure, 1);
  EXPECT_EQ(white.at<cv::Vec3b>(0, 0)[0], 255);  // saturates
}

TEST(ColourPipeline, VignettingDarkensTheCornersToItsValue) {
  SensorSpec s = pipeline_sensor();
  s.colour.vignetting = 0.6;
  cv::Mat image = flat(200, 641, 481);
  apply_colour_sensor(image, s, {}, 1);
  const double centre = linear(image.at<cv::Vec3b>(240, 320)[1]);
  const double corner = linear(image.at<cv::Vec3b>(0, 0)[1]);
  EXPECT_NEAR(centre, linear(200), 0.005);
  EXPECT_NEAR(corner / centre, 0.6, 0.012);
}

// Shot and read noise: the standard deviation at each brightness and gain
// is the model's, sqrt(e + r^2) electrons carried through the tone curve.
TEST(ColourPipeline, NoiseFollowsShotAndReadNoiseAtEveryBrightnessAndGain) {
  SensorSpec s = pipeline_sensor();
  s.colour.full_well = 5000;
  s.colour.read_noise = 8;
  for (double gain : {1.0, 4.0}) {
    for (int v : {60, 120, 200}) {
      cv::Mat image = flat(v, 400, 300);
      ColourCapture capture;
      capture.gain = gain;
      apply_colour_sensor(image, s, capture, 3);
      cv::Scalar mean, stddev;
      cv::meanStdDev(image.reshape(1), mean, stddev);
      const double lin = linear(v);
      const double electrons = lin * s.colour.full_well / gain;
      const double sigma_linear = std::sqrt(electrons + 64.0) * gain / s.colour.full_well;
      const double slope = (srgb_encode(lin + 1e-4) - srgb_encode(lin - 1e-4)) / 2e-4;
      const double curvature =
          (srgb_encode(lin + 1e-3) - 2 * srgb_encode(lin) + srgb_encode(lin - 1e-3)) / 1e-6;
      const double expected = 255 * slope * sigma_linear;
      const double with_rounding = std::sqrt(expected * expected + 1.0 / 12);
      EXPECT_NEAR(stddev[0], with_rounding, 0.1 * with_rounding)
          << "grey " << v << " gain " << gain;
      // The tone curve is concave: noise lowers the mean by f''/2 sigma^2.
      const double bias = 255 * 0.5 * curvature * sigma_linear * sigma_linear;
      EXPECT_NEAR(mean[0], v + bias, 0.15) << "grey " << v << " gain " << gain;
    }
  }
}

// The mosaic keeps one colour per pixel and the driver's demosaicing
// restores flat colours (so the pattern and OpenCV's naming agree); edges
// get colour fringes.
TEST(ColourPipeline, BayerMosaicRestoresFlatColoursAndFringesEdges) {
  for (const char* method : {"bilinear", "edge_aware"}) {
    for (const char* pattern : {"rggb", "grbg", "gbrg", "bggr"}) {
      SensorSpec s = pipeline_sensor();
      s.colour.demosaic = method;
      s.colour.bayer = pattern;
      cv::Mat patch(48, 64, CV_8UC3, cv::Scalar(40, 90, 200));  // B, G, R
      apply_colour_sensor(patch, s, {}, 1);
      const cv::Vec3b inside = patch.at<cv::Vec3b>(24, 32);
      EXPECT_NEAR(inside[0], 40, 1) << method << " " << pattern;
      EXPECT_NEAR(inside[1], 90, 1) << method << " " << pattern;
      EXPECT_NEAR(inside[2], 200, 1) << method << " " << pattern;
      cv::Mat edge = flat(20);
      edge(cv::Rect(31, 0, 33, 48)).setTo(cv::Scalar(230, 230, 230));
      apply_colour_sensor(edge, s, {}, 1);
      int fringe = 0;
      for (int x = 28; x < 36; ++x) {
        const cv::Vec3b p = edge.at<cv::Vec3b>(24, x);
        fringe = std::max({fringe, std::abs(p[0] - p[1]), std::abs(p[2] - p[1])});
      }
      EXPECT_GT(fringe, 10) << method << " " << pattern;
    }
  }
}

// The lens's point-spread function: a step edge's 10-90 % rise in linear
// light is 2.563 sigma wide.
TEST(ColourPipeline, LensBlurWidensAnEdgeByItsSigma) {
  SensorSpec s = pipeline_sensor();
  s.colour.lens_blur = 2.0;
  cv::Mat edge = flat(0, 64, 16);
  edge(cv::Rect(32, 0, 32, 16)).setTo(cv::Scalar(255, 255, 255));
  apply_colour_sensor(edge, s, {}, 1);
  std::vector<double> row;
  for (int x = 0; x < 64; ++x) row.push_back(linear(edge.at<cv::Vec3b>(8, x)[1]));
  auto crossing = [&](double level) {
    for (int x = 1; x < 64; ++x)
      if (row[x] >= level) return x - 1 + (level - row[x - 1]) / (row[x] - row[x - 1]);
    return 0.0;
  };
  EXPECT_NEAR(crossing(0.9) - crossing(0.1), 2.563 * 2.0, 0.3);
}

TEST(ColourPipeline, JpegIsLossyAndDeterministicAndNoiseFollowsTheSeed) {
  SensorSpec s = pipeline_sensor();
  s.colour.jpeg_quality = 60;
  s.colour.full_well = 4000;
  cv::Mat texture(96, 128, CV_8UC3);
  cv::randu(texture, 0, 255);
  cv::GaussianBlur(texture, texture, cv::Size(0, 0), 1.5);
  cv::Mat a = texture.clone(), b = texture.clone(), c = texture.clone();
  apply_colour_sensor(a, s, {}, 11);
  apply_colour_sensor(b, s, {}, 11);
  apply_colour_sensor(c, s, {}, 12);
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(a, c, cv::NORM_INF), 0.0);
  const double psnr = cv::PSNR(a, texture);
  EXPECT_GT(psnr, 28.0);
  EXPECT_LT(psnr, 45.0);
}

TEST(ColourPipeline, TheMeterReadsTheExposedImage) {
  const ColourPipelineSpec colour;
  cv::Mat grey = flat(118);
  EXPECT_NEAR(metered_brightness(grey, colour, {}), 118 / 255.0, 1e-3);
  ColourCapture darker;
  darker.row_light.assign(48, 0.25f);
  EXPECT_NEAR(metered_brightness(grey, colour, darker), srgb_encode(0.25 * linear(118)), 1e-3);
}

}  // namespace
}  // namespace depot::sim
