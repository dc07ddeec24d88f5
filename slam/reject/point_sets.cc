#include "slam/reject/point_sets.h"

namespace depot::slam {
namespace {

bool inside(const cv::Rect2f& box, const cv::Point2f& p) {
  return p.x >= box.x && p.y >= box.y && p.x < box.x + box.width && p.y < box.y + box.height;
}

}  // namespace

std::vector<float> keypoint_depths(const cv::Mat& depth,
                                   const std::vector<cv::KeyPoint>& keypoints) {
  std::vector<float> out(keypoints.size(), 0.0f);
  for (size_t i = 0; i < keypoints.size(); ++i) {
    const int x = static_cast<int>(keypoints[i].pt.x + 0.5f),
              y = static_cast<int>(keypoints[i].pt.y + 0.5f);
    if (x >= 0 && y >= 0 && x < depth.cols && y < depth.rows) out[i] = depth.at<float>(y, x);
  }
  return out;
}

std::vector<PointSet> assign_point_sets(const std::vector<cv::KeyPoint>& keypoints,
                                        const std::vector<Detection>& detections,
                                        const AprioriClasses& classes) {
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

void split_boxes_by_depth(const std::vector<cv::KeyPoint>& keypoints,
                          const std::vector<float>& depth, const std::vector<Detection>& detections,
                          const AprioriClasses& classes, float margin,
                          std::vector<PointSet>& sets) {
  std::vector<PointSet> out = sets;  // boxes are judged on the sets before any move
  for (const Detection& d : detections) {
    const MotionClass motion = classes.classify(d.class_name);
    if (motion == MotionClass::kStatic) continue;
    const bool dynamic = motion == MotionClass::kDynamic;
    std::vector<size_t> at_depth, no_depth;
    std::vector<float> depths;
    for (size_t i = 0; i < keypoints.size(); ++i) {
      if (sets[i] == PointSet::kP || !inside(d.box, keypoints[i].pt)) continue;
      (depth[i] > 0 ? at_depth : no_depth).push_back(i);
      if (depth[i] > 0) depths.push_back(depth[i]);
    }
    if (depths.size() < 5) continue;  // the object itself has no depth: decide nothing
    for (size_t i : no_depth) out[i] = PointSet::kP;
    if (!dynamic) continue;
    std::nth_element(depths.begin(), depths.begin() + depths.size() / 4, depths.end());
    const float object_depth = depths[depths.size() / 4];
    // Only Z: a point that is also in another box keeps the overlap rule.
    for (size_t i : at_depth)
      if (sets[i] == PointSet::kZ && depth[i] > object_depth + margin) out[i] = PointSet::kP;
  }
  sets = std::move(out);
}

std::vector<bool> inside_dynamic_boxes(const std::vector<cv::KeyPoint>& keypoints,
                                       const std::vector<Detection>& detections,
                                       const AprioriClasses& classes) {
  std::vector<bool> out(keypoints.size(), false);
  for (size_t k = 0; k < detections.size(); ++k) {
    if (classes.classify(detections[k].class_name) != MotionClass::kDynamic) continue;
    for (size_t i = 0; i < keypoints.size(); ++i)
      out[i] = out[i] || inside(detections[k].box, keypoints[i].pt);
  }
  return out;
}

}  // namespace depot::slam
