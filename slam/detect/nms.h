#pragma once
// Intersection over union and class-wise non-maximum suppression of
// detections.
#include <vector>

#include <opencv2/core.hpp>

#include "slam/detect/detection.h"

namespace depot::slam {

// Intersection area over union area; 0 when the union is empty.
float iou(const cv::Rect2f& a, const cv::Rect2f& b);

// Greedy class-wise NMS (as cv::dnn::NMSBoxes, per class): detections are
// taken in decreasing confidence; one is dropped when its IoU with an already
// kept detection of the same class (same class_id and class_name) exceeds
// `iou_threshold`. Detections of different classes never suppress each other.
// Returns the kept detections, most confident first (ties keep input order).
std::vector<Detection> non_max_suppression(std::vector<Detection> detections, float iou_threshold);

}  // namespace depot::slam
