#pragma once
// Scoring a binary segmentation mask against a true one, pixel by pixel, and
// against boxes when no true mask exists (hand-labelled real frames).
#include <vector>

#include <opencv2/core.hpp>

namespace depot::eval {

// Pixel counts of predicted against true masks, summed over frames.
struct MaskCounts {
  long true_positive = 0, false_positive = 0, false_negative = 0;
  // Both CV_8U of one size, non-zero = inside. Throws depot::Error otherwise.
  void add(const cv::Mat& predicted, const cv::Mat& truth);
  void add(const MaskCounts& other);
  double iou() const;        // TP / (TP + FP + FN); NaN when both masks are empty
  double precision() const;  // TP / (TP + FP); NaN when nothing is predicted
  double recall() const;     // TP / (TP + FN); NaN when nothing is true
};

// How a mask sits in a set of boxes: the share of the mask's pixels inside
// the boxes' union, and the share of the union the mask covers.
struct BoxCoverage {
  long mask_pixels = 0, box_pixels = 0, mask_in_boxes = 0;
  double inside() const;   // mask_in_boxes / mask_pixels (NaN for an empty mask)
  double covered() const;  // mask_in_boxes / box_pixels (NaN without boxes)
};
BoxCoverage box_coverage(const cv::Mat& mask, const std::vector<cv::Rect2f>& boxes);

}  // namespace depot::eval
