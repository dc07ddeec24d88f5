#pragma once
#include <opencv2/core.hpp>

namespace depot::sim {

// What the camera sees at one instant, exactly (no sensor model).
struct RenderedFrame {
  cv::Mat bgr;       // CV_8UC3, top row first
  cv::Mat depth;     // CV_32F, metres along the optical axis, 0 = no surface
  cv::Mat instance;  // CV_16U, instance id per pixel, 0 = no surface
};

}  // namespace depot::sim
