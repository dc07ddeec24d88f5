#pragma once
// Matching detections to ground-truth boxes, as detection benchmarks do
// (PASCAL VOC, COCO): detections in order of falling confidence, each taking
// the free ground-truth box it overlaps most, if that overlap reaches the
// IoU threshold and the pair is allowed (e.g. same class).
#include <functional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace depot::eval {

// A ground-truth box: an object's class, its box and how many of its pixels
// are visible (for buckets and the "clearly visible" rule).
struct TruthObject {
  std::string class_name;
  cv::Rect2f box;  // pixels
  double visible_pixels = 0.0;
  std::string model;  // the catalogue model a simulated object is drawn from, or ""
};

// A detection as scored: the detector's own label (before any class
// mapping), its confidence and box.
struct ScoredDetection {
  std::string label;
  float confidence = 0.0f;
  cv::Rect2f box;  // pixels
};

// Intersection over union of two boxes (0 when both are empty).
double box_iou(const cv::Rect2f& a, const cv::Rect2f& b);

// Which truth box each detection took and which detection each truth box
// got (-1: none).
struct Matching {
  std::vector<int> truth_of_detection;
  std::vector<int> detection_of_truth;
};

// An empty matching of these sizes.
Matching no_matches(size_t truth, size_t detections);

// Greedy matching: the detections not yet matched in `m`, by decreasing
// confidence (ties keep their order), each take the truth box not yet
// matched with the highest IoU >= min_iou among those `allowed(detection,
// truth)` accepts (ties: the first). Extends `m`, so a second pass with a
// looser rule matches only what the first left free.
void greedy_match(const std::vector<TruthObject>& truth,
                  const std::vector<ScoredDetection>& detections, double min_iou,
                  const std::function<bool(size_t, size_t)>& allowed, Matching& m);

}  // namespace depot::eval
