#pragma once
// The dense static map of a run (`depot slam run --dense-map F.ply`): the
// final keyframes' depth images, read again from the dataset, fused with
// slam::DenseCloud at the keyframes' final poses (after loop closing and
// global adjustment) with moving pixels left out, written as PLY.
#include <map>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "common/tum_io.h"
#include "eval/motion_truth.h"
#include "slam/dense/dense_cloud.h"
#include "slam/io/rgbd_sequence.h"
#include "slam/reject/rejection_filter.h"
#include "tools/runner/frame_observer.h"

namespace depot::runner {

// What leaves moving pixels out of a dense map: the rejection's masks of
// the keyframes (slam::RejectionFilter::moving_mask), the simulated
// dataset's labels of moving objects, or nothing.
enum class DenseMask { kRejection, kLabels, kNone };
// rejection | labels | none; depot::Error("--dense-mask: ...") otherwise.
DenseMask parse_dense_mask(const std::string& name);

struct DenseMapResult {
  size_t points = 0;
  int keyframes = 0;      // keyframes fused
  int without_frame = 0;  // left out: their frame is not in the sequence (a loaded map's)
  int without_mask = 0;   // left out: no rejection mask of this run (a loaded map's)
};

// Keyframes whose frame is not in `sequence` (from a loaded map) are left
// out. With kRejection `rejection_masks` holds each keyframe's mask by
// timestamp (one missing: its keyframe is left out); with kLabels `truth`
// gives them. Writes `path` through a staged file. Throws depot::Error
// naming `path`, and writes nothing, when no keyframe could be fused or the
// fused views leave no point.
DenseMapResult write_dense_map(const std::string& path, const slam::RgbdSequence& sequence,
                               const slam::PinholeCamera& camera,
                               const std::vector<StampedPose>& keyframes, DenseMask mask,
                               const std::map<double, cv::Mat>& rejection_masks,
                               const eval::MotionTruth* truth,
                               const slam::DenseCloudParams& params);

// Where the dense map of atlas map `map` (>= 1) of a run with `--dense-map
// path` goes: "d.ply" -> "d.map1.ply" (the main map, 0, is `path` itself).
std::string dense_map_path(const std::string& path, int map);

// `--dense-map F.ply` as an observer of the run: keeps the rejection's
// masks of the frames made keyframes and writes the map on on_finish, at
// the keyframes' final poses: the main map to F.ply and each other map of
// the atlas (frames tracked after a loss, never merged) to its own file
// (dense_map_path), as its frame is not the main map's.
class DenseMapBuilder : public FrameObserver {
 public:
  // Checks before any work: `path` writable, the cloud's parameters, labels
  // only on a simulated dataset (`truth`), rejection masks only from a
  // filter that makes them (`mode` names it in the error).
  DenseMapBuilder(const std::string& path, DenseMask mask, const slam::DenseCloudParams& params,
                  const slam::PinholeCamera& camera, const slam::RejectionFilter* filter,
                  const eval::MotionTruth* truth, const std::string& dataset,
                  const std::string& mode);
  void on_frame(const FrameRecord& frame) override;
  void on_finish(const slam::System& system, const slam::RgbdSequence& sequence,
                 RunSummary& summary) override;

 private:
  std::string path_;
  DenseMask mask_;
  slam::DenseCloudParams params_;
  slam::PinholeCamera camera_;
  const slam::RejectionFilter* filter_;
  const eval::MotionTruth* truth_;
  std::map<double, cv::Mat> keyframe_masks_;  // rejection masks by keyframe timestamp
};

}  // namespace depot::runner
