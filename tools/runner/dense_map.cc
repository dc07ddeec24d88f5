#include "tools/runner/dense_map.h"

#include <filesystem>

#include "common/error.h"
#include "common/staged_file.h"

namespace fs = std::filesystem;

namespace depot::runner {

DenseMask parse_dense_mask(const std::string& name) {
  if (name == "rejection") return DenseMask::kRejection;
  if (name == "labels") return DenseMask::kLabels;
  if (name == "none") return DenseMask::kNone;
  fail("--dense-mask", "unknown mask '" + name + "' (expected rejection, labels or none)");
}

DenseMapResult write_dense_map(const std::string& path, const slam::RgbdSequence& sequence,
                               const slam::PinholeCamera& camera,
                               const std::vector<StampedPose>& keyframes, DenseMask mask,
                               const std::map<double, cv::Mat>& rejection_masks,
                               const eval::MotionTruth* truth,
                               const slam::DenseCloudParams& params) {
  std::map<double, size_t> frame_at;  // rgb timestamp -> frame index
  for (size_t i = 0; i < sequence.size(); ++i) frame_at[sequence.timestamp(i)] = i;
  slam::DenseCloud cloud(camera, params);
  DenseMapResult result;
  cv::Mat bgr, depth;
  for (const StampedPose& keyframe : keyframes) {
    const auto frame = frame_at.find(keyframe.timestamp);
    if (frame == frame_at.end()) {
      ++result.without_frame;
      continue;
    }
    cv::Mat moving;
    if (mask == DenseMask::kRejection) {
      const auto found = rejection_masks.find(keyframe.timestamp);
      if (found == rejection_masks.end()) {
        ++result.without_mask;
        continue;
      }
      moving = found->second;
    } else if (mask == DenseMask::kLabels) {
      moving = truth->moving_mask(keyframe.timestamp);
    }
    sequence.load(frame->second, bgr, depth);
    cloud.add_view(keyframe.pose, depth, bgr, moving);
    ++result.keyframes;
  }
  if (result.keyframes == 0)
    fail(path, "no keyframe to fuse: of " + std::to_string(keyframes.size()) + ", " +
                   std::to_string(result.without_frame) + " have no frame in this dataset and " +
                   std::to_string(result.without_mask) +
                   " no rejection mask of this run (a loaded map's; --dense-mask labels or none "
                   "fuses those of this dataset)");
  const std::vector<slam::PlyPoint> points = cloud.points();
  if (points.empty())
    fail(path, "the " + std::to_string(result.keyframes) +
                   " keyframes fused leave no point (seen from too few views? --dense-min-views)");
  slam::write_ply(path, points, "views");
  result.points = points.size();
  return result;
}

DenseMapBuilder::DenseMapBuilder(const std::string& path, DenseMask mask,
                                 const slam::DenseCloudParams& params,
                                 const slam::PinholeCamera& camera,
                                 const slam::RejectionFilter* filter,
                                 const eval::MotionTruth* truth, const std::string& dataset,
                                 const std::string& mode)
    : path_(path), mask_(mask), params_(params), camera_(camera), filter_(filter), truth_(truth) {
  check_output_file(path);
  slam::DenseCloud check_params(camera, params);
  if (mask == DenseMask::kLabels && !truth)
    fail(dataset, "has no labels: --dense-mask labels needs a simulated dataset");
  if (mask == DenseMask::kRejection && (!filter || filter->mode() == slam::RejectionMode::kOrbLk))
    fail("--dense-mask rejection",
         "mode " + mode +
             " leaves no moving mask (orb+yolo, full and masked do); give --dense-mask labels "
             "or none");
}

void DenseMapBuilder::on_frame(const FrameRecord& frame) {
  if (mask_ == DenseMask::kRejection && frame.result.stats.new_keyframe)
    keyframe_masks_[frame.timestamp] = filter_->moving_mask(frame.bgr.size());
}

std::string dense_map_path(const std::string& path, int map) {
  if (map == 0) return path;
  const fs::path p(path);
  return (p.parent_path() /
          (p.stem().string() + ".map" + std::to_string(map) + p.extension().string()))
      .string();
}

void DenseMapBuilder::on_finish(const slam::System& system, const slam::RgbdSequence& sequence,
                                RunSummary& summary) {
  const std::vector<std::vector<StampedPose>> maps = system.keyframe_trajectories();
  const DenseMapResult cloud =
      write_dense_map(path_, sequence, camera_, maps.empty() ? std::vector<StampedPose>{} : maps[0],
                      mask_, keyframe_masks_, truth_, params_);
  summary.dense_points = cloud.points;
  summary.dense_keyframes = cloud.keyframes;
  summary.dense_left_out = cloud.without_frame + cloud.without_mask;
  for (size_t m = 1; m < maps.size(); ++m) {
    RunSummary::DenseMapFile file;
    file.map = static_cast<int>(m);
    const std::string path = dense_map_path(path_, file.map);
    try {
      check_output_file(path);
      const DenseMapResult other = write_dense_map(path, sequence, camera_, maps[m], mask_,
                                                   keyframe_masks_, truth_, params_);
      file.path = path;
      file.points = other.points;
      file.keyframes = other.keyframes;
    } catch (const Error& e) {
      // A short-lived map may be too small to fuse: the main map still stands.
      file.reason = e.what();
    }
    summary.dense_other_maps.push_back(file);
  }
}

}  // namespace depot::runner
