#pragma once
// Object detections as the rejection stage consumes them: class, confidence
// and an axis-aligned box in pixels.
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace depot::slam {

struct Detection {
  std::string class_name;  // e.g. "person" (names come from configuration)
  int class_id = -1;       // index in the detector's class list
  float confidence = 0.0f;
  cv::Rect2f box;  // pixels: x, y = top-left corner, width, height
};

// PAPER.md Eq. 8: YOLO's normalised centre format (X, Y, W, H) to pixels for
// an image of width L and height D: x1 = (X - W/2) L, x2 = (X + W/2) L,
// y1 = (Y - H/2) D, y2 = (Y + H/2) D (top-left has the smaller y).
inline cv::Rect2f yolo_to_pixels(float X, float Y, float W, float H, int L, int D) {
  const float x1 = (X - W / 2) * L, x2 = (X + W / 2) * L;
  const float y1 = (Y - H / 2) * D, y2 = (Y + H / 2) * D;
  return {x1, y1, x2 - x1, y2 - y1};
}

// Detects objects in one colour frame. Implementations: YOLOv5 ONNX, Darknet
// YOLO, FastestDet (OpenCV dnn), the simulated detector, and a detections file.
class Detector {
 public:
  virtual ~Detector() = default;
  // bgr: CV_8UC3. `timestamp` and `frame_index` identify the frame for
  // detectors that replay or simulate per-frame results.
  virtual std::vector<Detection> detect(const cv::Mat& bgr, double timestamp, long frame_index) = 0;
  virtual std::string name() const = 0;
  // The classes it can output (empty when unknown), to check class tables.
  virtual std::vector<std::string> class_names() const { return {}; }
};

}  // namespace depot::slam
