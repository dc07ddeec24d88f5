#pragma once
// A text file of precomputed detections, so boxes can be computed once (or by
// another tool) and replayed. One detection a line:
//
//   # comments start with '#'; blank lines are ignored
//   timestamp class_name confidence x1 y1 x2 y2
//   1341846313.592026 person 0.87 310.5 0 492 480
//
// timestamp in seconds (the frame's rgb timestamp); class_name without white
// space; confidence in [0, 1]; the box in pixels (float), top-left (x1, y1)
// and bottom-right (x2, y2), x2 >= x1 and y2 >= y1 (x2 = x + width as in
// Detection::box). Lines need not be sorted; lines with the same timestamp
// form one frame. A frame without detections has no line.
#include <string>
#include <vector>

#include "slam/detect/detection.h"

namespace depot::slam {

struct DetectionFrame {
  double timestamp = 0.0;
  std::vector<Detection> detections;
};

// Writes `frames` in order (atomically: all of it or nothing). Timestamps
// with 6 decimals, confidence and corners in the shortest form that reads
// back as the same float. Throws depot::Error "<path>: <problem>" for a class
// name that is empty or contains white space, a non-finite value or a box of
// negative size.
void write_detections_file(const std::string& path, const std::vector<DetectionFrame>& frames);

// Reads a detections file into frames sorted by timestamp (detections in file
// order). With `class_names`, every class must be one of them and class_id
// is its index; without, class_id is -1. Throws depot::Error
// "<path>:<line>: <problem>" for a wrong field count, a field that is not a
// number, NaN/inf, a confidence outside [0, 1], x2 < x1, y2 < y1, a negative
// timestamp or an unknown class; "<path>: cannot open file" when unreadable.
std::vector<DetectionFrame> read_detections_file(const std::string& path,
                                                 const std::vector<std::string>& class_names = {});

// Replays a detections file: detect() returns the detections of the frame
// whose timestamp is nearest to the one asked for, within 1e-4 s, and none
// when the file has no such frame. The image is not looked at.
class FileDetector : public Detector {
 public:
  explicit FileDetector(const std::string& path, const std::vector<std::string>& class_names = {});
  explicit FileDetector(std::vector<DetectionFrame> frames, std::string label = "memory");

  std::vector<Detection> detect(const cv::Mat& bgr, double timestamp, long frame_index) override;
  std::string name() const override { return "file:" + label_; }
  // The class list given, else the classes the file names (first use order).
  std::vector<std::string> class_names() const override;

  // The frame within 1e-4 s of `timestamp`, or nullptr.
  const DetectionFrame* find(double timestamp) const;
  const std::vector<DetectionFrame>& frames() const { return frames_; }

 private:
  std::vector<DetectionFrame> frames_;  // sorted by timestamp
  std::string label_;
  std::vector<std::string> class_names_;
};

}  // namespace depot::slam
