#pragma once
// The ground-truth boxes of a simulated dataset, per frame: rgb.txt (the
// frames), classes.txt (the detectable classes), calibration.yaml (the image
// size) and boxes.txt (read by dataset/boxes.h), each box checked against
// the other three. The simulated detector and `depot eval detector` both
// use it.
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace depot::slam {

// One line of a dataset's boxes.txt.
struct TruthBox {
  int id = 0;  // instance id (objects.json, labels/)
  std::string class_name;
  int class_id = -1;                   // index in classes.txt
  int x1 = 0, y1 = 0, x2 = 0, y2 = 0;  // pixels, x2/y2 exclusive
  int visible_pixels = 0;
  bool moving = false;

  int area() const { return (x2 - x1) * (y2 - y1); }
  cv::Rect2f rect() const {
    return cv::Rect2f(static_cast<float>(x1), static_cast<float>(y1), static_cast<float>(x2 - x1),
                      static_cast<float>(y2 - y1));
  }
};

struct DatasetBoxes {
  std::vector<double> timestamps;             // rgb.txt order (increasing)
  std::vector<std::string> rgb_files;         // rgb.txt paths, relative to the dataset folder
  std::vector<std::string> classes;           // classes.txt; TruthBox::class_id indexes it
  cv::Size image_size;                        // calibration.yaml
  std::vector<std::vector<TruthBox>> frames;  // per rgb.txt frame, in boxes.txt order
};

// Reads the four files of `dataset_dir`. Throws depot::Error naming the file
// (and line) when one is missing or malformed: a box outside the image, a
// class not in classes.txt, a timestamp that is not a frame of rgb.txt.
DatasetBoxes read_dataset_boxes(const std::string& dataset_dir);

// The entry of the increasing `timestamps` within 1e-4 s of `t`, or -1.
long nearest_timestamp(const std::vector<double>& timestamps, double t);

}  // namespace depot::slam
