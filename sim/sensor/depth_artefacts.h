#pragma once
// Depth artefacts a real RGB-D camera adds beyond noise (sim/sensor/
// kinect_model.h), each off at 0 so datasets without them stay as they were:
// - flying pixels: beside a depth edge the sensor mixes the near and the far
//   surface and reports a depth between them, on neither;
// - dark dropout: infrared light absorbed by dark surfaces returns no depth
//   (the colour's brightness stands in for the material's IR response);
// - misregistration: the depth image sits a few pixels off the colour
//   image, as on a rig whose depth-to-colour registration is not calibrated.
// Labels and truth stay the colour image's (they describe the world).
#include <cstdint>

#include <opencv2/core.hpp>

#include "sim/scenario/scenario.h"

namespace depot::sim {

// depth: CV_32F metres (0 = none), exact; bgr: the exact colour render.
// Flying pixels and dark dropout, in place.
void apply_depth_artefacts(cv::Mat& depth, const cv::Mat& bgr, const SensorSpec& sensor,
                           uint64_t seed);

// The depth image moved by the sensor's misregistration (pixels, nearest
// neighbour: a depth is never interpolated across an edge); uncovered
// borders have no depth.
cv::Mat misregister_depth(const cv::Mat& depth, const SensorSpec& sensor);

}  // namespace depot::sim
