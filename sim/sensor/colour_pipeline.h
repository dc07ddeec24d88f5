#pragma once
// What the colour camera makes of the light the renderer draws: light level
// and exposure, vignetting and the lens's softness, then the sensor (Bayer
// mosaic, shot and read noise, gain, saturation), the tone curve, the
// driver's demosaicing and JPEG. The render is taken as the camera's output
// at the reference exposure under light level 1 (sim/sensor/auto_exposure.h),
// encoded with sRGB's tone curve: the chain first undoes that curve, so
// light and exposure act on linear light as they do on a sensor.
//
// With every stage off (ColourPipelineSpec::any() false, constant light, no
// auto-exposure) the image is the render plus `rgb_noise` exactly as before
// the pipeline existed (sim/sensor/kinect_model.h apply_rgb_noise).
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "sim/scenario/scenario.h"

namespace depot::sim {

// How one frame was exposed (truth; written per frame to exposures.txt).
struct ColourCapture {
  double exposure = 0.0;  // s
  double gain = 1.0;
  double scale = 1.0;            // exposure x gain against the render's reference
  std::vector<float> row_light;  // mean light level each row saw; empty = 1
  // CV_32F per pixel: the radiance (x the render's white under light 1) of
  // daylight seen through an opening (sim/sensor/daylight.h), which the
  // hall's light level does not scale; 0 where none, empty when none at all.
  cv::Mat daylight;
};

// Applies the colour sensor to a render (CV_8UC3 BGR), in place. `seed`
// draws the noise; the same inputs give the same bytes.
void apply_colour_sensor(cv::Mat& bgr, const SensorSpec& sensor, const ColourCapture& capture,
                         uint64_t seed);

// The mean output brightness (0..1, Rec. 601 luma of the tone-mapped image,
// after saturation, before noise) the camera's meter reads from a render
// exposed as `capture`: what auto-exposure steers by. Samples every 4th
// pixel.
double metered_brightness(const cv::Mat& bgr, const ColourPipelineSpec& colour,
                          const ColourCapture& capture);

// Relative illumination of pixel (x, y) under `vignetting` (the corners'
// value): 1 - (1 - vignetting) rho^2, rho the distance from the image
// centre over the distance to its corners.
double vignetting_factor(double vignetting, double x, double y, int width, int height);

}  // namespace depot::sim
