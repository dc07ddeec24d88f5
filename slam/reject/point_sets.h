#pragma once
// PAPER.md "Point sets": each keypoint goes to exactly one of
//   Z (dynamic): inside a dynamic box and in no static/potential box;
//   Q (potentially dynamic): inside a potential box, or in a dynamic box that
//     overlaps a static/potential box there (the overlap rule: decided by
//     the flow test instead of thrown away);
//   P (static): all others.
#include <vector>

#include <opencv2/core.hpp>

#include "slam/detect/detection.h"
#include "slam/reject/apriori_classes.h"

namespace depot::slam {

enum class PointSet : uint8_t { kP = 0, kQ = 1, kZ = 2 };

std::vector<PointSet> assign_point_sets(const std::vector<cv::KeyPoint>& keypoints,
                                        const std::vector<Detection>& detections,
                                        const AprioriClasses& classes);

// Our extension: Z points lying more than `margin` (m) behind their box's
// object (the 25th percentile of the box's keypoint depths), or without
// depth (depth[i] <= 0: beyond the sensor's range or at an edge), move to Q.
void move_background_to_q(const std::vector<cv::KeyPoint>& keypoints,
                          const std::vector<float>& depth, const std::vector<Detection>& detections,
                          const AprioriClasses& classes, float margin, std::vector<PointSet>& sets);

// orb+yolo: inside any dynamic box at all (no overlap rule).
std::vector<bool> inside_dynamic_boxes(const std::vector<cv::KeyPoint>& keypoints,
                                       const std::vector<Detection>& detections,
                                       const AprioriClasses& classes);

}  // namespace depot::slam
