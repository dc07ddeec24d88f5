#include "sim/dataset/boxes.h"

#include <fmt/format.h>

#include <algorithm>

namespace depot::sim {

std::vector<InstanceBox> instance_boxes(const cv::Mat& instance, int min_pixels) {
  // A flat table indexed by id: one pass, no per-pixel lookups.
  std::vector<InstanceBox> boxes(65536);
  uint16_t max_id = 0;
  for (int y = 0; y < instance.rows; ++y) {
    const uint16_t* row = instance.ptr<uint16_t>(y);
    for (int x = 0; x < instance.cols; ++x) {
      const uint16_t id = row[x];
      if (id == 0) continue;
      InstanceBox& b = boxes[id];
      if (b.pixels == 0) {
        b = {id, x, y, x + 1, y + 1, 0};
        max_id = std::max(max_id, id);
      } else {
        b.x1 = std::min(b.x1, x);
        b.x2 = std::max(b.x2, x + 1);
        b.y2 = y + 1;  // rows come in order, so y1 is the first
      }
      ++b.pixels;
    }
  }
  std::vector<InstanceBox> out;
  for (int id = 1; id <= max_id; ++id)
    if (boxes[id].pixels > 0 && boxes[id].pixels >= min_pixels) out.push_back(boxes[id]);
  return out;
}

std::string yolo_line(int yolo_class, const InstanceBox& b, int width, int height) {
  return fmt::format("{} {:.6f} {:.6f} {:.6f} {:.6f}", yolo_class, 0.5 * (b.x1 + b.x2) / width,
                     0.5 * (b.y1 + b.y2) / height, static_cast<double>(b.x2 - b.x1) / width,
                     static_cast<double>(b.y2 - b.y1) / height);
}

}  // namespace depot::sim
