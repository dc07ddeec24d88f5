#include "slam/reject/point_sets.h"

namespace depot::slam {
namespace {

bool inside(const cv::Rect2f& box, const cv::Point2f& p) {
  return p.x >= box.x && p.y >= box.y && p.x < box.x + box.width && p.y < box.y + box.height;
}

}  // namespace

std::vector<PointSet> assign_point_sets(const std::vector<cv::KeyPoint>& keypoints,
                                        const std::vector<Detection>& detections, const AprioriClasses& classes) {
  std::vector<PointSet> sets(keypoints.size(), PointSet::kP);
  std::vector<MotionClass> motion;
  for (const auto& d : detections) motion.push_back(classes.classify(d.class_name));
  for (size_t i = 0; i < keypoints.size(); ++i) {
    bool in_dynamic = false, in_other = false, in_potential = false;
    for (size_t k = 0; k < detections.size(); ++k) {
      if (!inside(detections[k].box, keypoints[i].pt)) continue;
      if (motion[k] == MotionClass::kDynamic) {
        in_dynamic = true;
      } else {
        in_other = true;
        in_potential |= motion[k] == MotionClass::kPotentiallyDynamic;
      }
    }
    if (in_dynamic && !in_other) {
      sets[i] = PointSet::kZ;
    } else if (in_potential || (in_dynamic && in_other)) {
      sets[i] = PointSet::kQ;
    }
  }
  return sets;
}

std::vector<bool> inside_dynamic_boxes(const std::vector<cv::KeyPoint>& keypoints,
                                       const std::vector<Detection>& detections, const AprioriClasses& classes) {
  std::vector<bool> out(keypoints.size(), false);
  for (size_t k = 0; k < detections.size(); ++k) {
    if (classes.classify(detections[k].class_name) != MotionClass::kDynamic) continue;
    for (size_t i = 0; i < keypoints.size(); ++i) out[i] = out[i] || inside(detections[k].box, keypoints[i].pt);
  }
  return out;
}

}  // namespace depot::slam
