#pragma once
// Ground-truth boxes of the visible instances of a label image.
#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace depot::sim {

struct InstanceBox {
  uint16_t id = 0;
  int x1 = 0, y1 = 0;  // first pixel column/row covered
  int x2 = 0, y2 = 0;  // one past the last (so width = x2 - x1)
  int pixels = 0;      // visible pixels
};

// Tight boxes of every instance with at least `min_pixels` visible pixels,
// sorted by id. `instance` is CV_16U.
std::vector<InstanceBox> instance_boxes(const cv::Mat& instance, int min_pixels);

// YOLO form: "class cx cy w h", normalised by the image size.
std::string yolo_line(int yolo_class, const InstanceBox& box, int width, int height);

}  // namespace depot::sim
