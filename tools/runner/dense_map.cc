#include "tools/runner/dense_map.h"

#include "common/error.h"

namespace depot::runner {

DenseMask parse_dense_mask(const std::string& name) {
  if (name == "rejection") return DenseMask::kRejection;
  if (name == "labels") return DenseMask::kLabels;
  if (name == "none") return DenseMask::kNone;
  fail("--dense-mask", "unknown mask '" + name + "' (expected rejection, labels or none)");
}

DenseMapResult write_dense_map(const std::string& path, const slam::TumSequence& sequence,
                               const slam::PinholeCamera& camera,
                               const std::vector<StampedPose>& keyframes, DenseMask mask,
                               const std::map<double, cv::Mat>& rejection_masks,
                               const eval::MotionTruth* truth,
                               const slam::DenseCloudParams& params) {
  std::map<double, size_t> frame_at;  // rgb timestamp -> frame index
  for (size_t i = 0; i < sequence.size(); ++i) frame_at[sequence.entry(i).rgb_timestamp] = i;
  slam::DenseCloud cloud(camera, params);
  DenseMapResult result;
  cv::Mat bgr, depth;
  for (const StampedPose& keyframe : keyframes) {
    const auto frame = frame_at.find(keyframe.timestamp);
    if (frame == frame_at.end()) continue;
    cv::Mat moving;
    if (mask == DenseMask::kRejection) {
      const auto found = rejection_masks.find(keyframe.timestamp);
      if (found == rejection_masks.end()) continue;
      moving = found->second;
    } else if (mask == DenseMask::kLabels) {
      moving = truth->moving_mask(keyframe.timestamp);
    }
    sequence.load(frame->second, bgr, depth);
    cloud.add_view(keyframe.pose, depth, bgr, moving);
    ++result.keyframes;
  }
  const std::vector<slam::PlyPoint> points = cloud.points();
  slam::write_ply(path, points, "views");
  result.points = points.size();
  return result;
}

}  // namespace depot::runner
