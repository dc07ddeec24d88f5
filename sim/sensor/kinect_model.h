#pragma once
// A Kinect-v1-like RGB-D sensor model applied to exact renders: depth noise
// and quantisation in disparity space (so error grows with depth squared),
// no depth outside [min, max] range and in the projector's shadow beside
// depth edges, and mild RGB noise. Seeded per frame: deterministic.
#include <cstdint>

#include <opencv2/core.hpp>

#include "sim/scenario/scenario.h"

namespace depot::sim {

// depth: CV_32F metres (0 = none) -> noisy CV_32F metres (0 = no data).
cv::Mat apply_depth_model(const cv::Mat& depth, const SensorSpec& sensor, double focal,
                          uint64_t seed);

// Adds zero-mean noise of `sigma` grey levels to each channel, in place.
void apply_rgb_noise(cv::Mat& bgr, double sigma, uint64_t seed);

// Metres -> 16-bit PNG units (value = metres x factor, 0 = no data).
cv::Mat depth_to_u16(const cv::Mat& depth, double factor);

}  // namespace depot::sim
