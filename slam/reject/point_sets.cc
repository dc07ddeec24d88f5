#include "slam/reject/point_sets.h"

namespace depot::slam {
namespace {

bool inside(const cv::Rect2f& box, const cv::Point2f& p) {
  return p.x >= box.x && p.y >= box.y && p.x < box.x + box.width && p.y < box.y + box.height;
}

}  // namespace

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

void move_background_to_q(const std::vector<cv::KeyPoint>& keypoints,
                          const std::vector<float>& depth, const std::vector<Detection>& detections,
                          const AprioriClasses& classes, float margin,
                          std::vector<PointSet>& sets) {
  for (const Detection& d : detections) {
    if (classes.classify(d.class_name) != MotionClass::kDynamic) continue;
    std::vector<size_t> members, unknown;
    std::vector<float> depths;
    for (size_t i = 0; i < keypoints.size(); ++i) {
      if (sets[i] != PointSet::kZ || !inside(d.box, keypoints[i].pt)) continue;
      if (depth[i] <= 0) {
        unknown.push_back(i);
        continue;
      }
      members.push_back(i);
      depths.push_back(depth[i]);
    }
    if (depths.size() < 5) continue;
    // No depth inside a box whose object has depth: out of the sensor's
    // range (far background) or a depth edge, so not the object itself.
    for (size_t i : unknown) sets[i] = PointSet::kQ;
    // The object is in front of what surrounds it in its box.
    std::nth_element(depths.begin(), depths.begin() + depths.size() / 4, depths.end());
    const float object_depth = depths[depths.size() / 4];
    for (size_t i : members)
      if (depth[i] > object_depth + margin) sets[i] = PointSet::kQ;
  }
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
