#pragma once
// A simulated object detector for the simulator's datasets: it reads the
// ground-truth boxes of a frame (boxes.txt) and degrades them the way a real
// YOLO does (sim_detector_config.h): misses that are likelier for small and
// occluded objects, localisation jitter and scale error, false positives,
// class confusion, confidence falling with difficulty, and latency.
//
// It reads only the dataset's files (rgb.txt, boxes.txt, classes.txt,
// calibration.yaml), never the simulator's code. Everything is seeded: frame
// i's detections depend only on the config, the dataset and i. Every real
// object draws from its own stream (seed, frame, instance id) with a fixed
// number of draws, and false positives from another, so changing one setting
// (say the jitter) leaves the other random decisions (which boxes are missed)
// unchanged.
//
// The model, per ground-truth box of area A (pixels), visible pixels V, in an
// image of W x H pixels:
//   smallness  s = clamp(1 - sqrt(A / (small_area W H)), 0, 1)
//   fill       f = V / A;  occlusion o = clamp(1 - f / f_class, 0, 1), where
//              f_class = reference_fill(class) (an unoccluded object's fill)
//   difficulty d = 1 - (1 - s)(1 - o)
//   P(miss)      = 1 - (1 - m)(1 - small_miss_boost s)(1 - occlusion_miss o),
//                  m = class_miss_rate of the box's class, else miss_rate
//   box          = centre + N(0, jitter (1 + g d)) x size,
//                  size x exp(N(0, scale_error (1 + g d))) per axis,
//                  g = hard_jitter_gain; clipped to the image (dropped if empty)
//   confidence   = clamp(max_c - (max_c - min_c) k d + N(0, confidence_noise), min_c, 1),
//                  k = confidence_drop
// Detections of real objects come in boxes.txt order, false positives after.
#include <string>
#include <vector>

#include "slam/detect/detection.h"
#include "slam/detect/sim_detector_config.h"
#include "slam/detect/truth_boxes.h"

namespace depot::slam {

// The model's terms from a box's numbers (what SimDetector's members compute
// from a TruthBox; the calibration's fit uses them too): smallness of a box
// of `area` pixels in an image of `image_area` pixels, and the difficulty of
// a box of this smallness and occlusion.
double model_smallness(double area, double image_area, double small_area);
double model_difficulty(double smallness, double occlusion);

class SimDetector : public Detector {
 public:
  // Reads `dataset_dir`'s rgb.txt, boxes.txt, classes.txt and
  // calibration.yaml. Throws depot::Error naming the file (and line) when one
  // is missing or malformed, and for an invalid config.
  explicit SimDetector(const std::string& dataset_dir, const SimDetectorConfig& config = {});

  // The frame is found by its rgb timestamp (within 1e-4 s) in rgb.txt;
  // with latency k the detections of the rgb.txt frame k before it are
  // returned (none for the first k frames). `bgr` is not looked at, but when
  // given it must have the dataset's image size. Throws depot::Error for a
  // timestamp that is not a frame of the dataset. `frame_index` is not used:
  // the dataset's own frame order defines the lag and the random streams.
  std::vector<Detection> detect(const cv::Mat& bgr, double timestamp, long frame_index) override;
  std::string name() const override { return config_.perfect ? "sim-perfect" : "sim"; }

  // Detections of the rgb.txt frame `index`, without latency. Const and
  // thread-safe.
  std::vector<Detection> detect_frame(size_t index) const;

  // The dataset.
  size_t frame_count() const { return data_.timestamps.size(); }
  double frame_timestamp(size_t index) const { return data_.timestamps.at(index); }
  // The rgb.txt frame within 1e-4 s of `timestamp`, or -1.
  long find_frame(double timestamp) const;
  const std::vector<TruthBox>& truth(size_t index) const { return data_.frames.at(index); }
  // classes.txt; class_id indexes it.
  std::vector<std::string> class_names() const override { return data_.classes; }
  cv::Size image_size() const { return data_.image_size; }
  const SimDetectorConfig& config() const { return config_; }

  // The model's terms (header comment), each in [0, 1].
  double smallness(const TruthBox& box) const;
  double occlusion(const TruthBox& box) const;
  double difficulty(const TruthBox& box) const;
  double miss_probability(const TruthBox& box) const;
  // The miss rate of a large, unoccluded box of the class (class_miss_rate,
  // else miss_rate).
  double class_miss_rate(const std::string& class_name) const;
  // Fill of an unoccluded object of the class: the 90th percentile of the
  // class's fills in boxes.txt, or config().default_fill with fewer than 10
  // boxes.
  double reference_fill(const std::string& class_name) const;

 private:
  // The detection of one real object, or false when it is missed.
  bool detect_box(const TruthBox& box, size_t frame, Detection& out) const;
  void add_false_positives(size_t frame, std::vector<Detection>& out) const;

  std::string dir_;
  SimDetectorConfig config_;
  DatasetBoxes data_;                   // rgb.txt frames, classes, image size, boxes
  std::vector<double> reference_fill_;  // per class id
  std::vector<double> miss_rate_;       // per class id
  std::vector<double> confusion_rate_;  // per class id
  // Sizes (w, h) of all ground-truth boxes per class id (false positives).
  std::vector<std::vector<cv::Size>> class_sizes_;
  std::vector<std::vector<int>> confusions_;  // per class id: partner class ids
  cv::Size image_size_;
};

}  // namespace depot::slam
