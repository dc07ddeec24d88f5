#pragma once
// A picture of one frame's rejection, for people to look at: the tracked
// boxes (detected: thick; carried over a missed detection: thin) and their
// object masks tinted (dynamic red, potentially dynamic blue), and every
// keypoint coloured by its decision. With the simulator's truth:
//   green   kept, static            red     rejected, moving (right)
//   yellow  kept, moving (missed)   magenta rejected, static (thrown away)
//   cyan    boundary point (either decision; see eval/motion_truth.h)
// Without truth: green kept, red rejected.
#include <cstddef>
#include <fstream>
#include <string>

#include <opencv2/core.hpp>

#include "common/staged_directory.h"
#include "eval/motion_truth.h"
#include "slam/reject/rejection_filter.h"
#include "tools/runner/frame_observer.h"

namespace depot::runner {

// The folder the pictures go to: index.txt and frames/NNNNNN.png.
inline OutputKind overlay_folder_kind() {
  return {"rejection pictures", "index.txt", {"index.txt", "frames"}};
}

// bgr: the frame (CV_8UC3); truth may be null. Returns a new CV_8UC3 image.
cv::Mat draw_rejection_overlay(const cv::Mat& bgr, const slam::RejectionFilter& filter,
                               const eval::MotionTruth::KeypointTruth* truth);

// `--overlays DIR`: the picture of every n-th frame (frames need a
// rejection filter), listed in index.txt; the folder appears on commit().
class OverlayFolder : public FrameObserver {
 public:
  // Stages `path`, which must be missing or empty (common/staged_directory.h).
  OverlayFolder(const std::string& path, size_t every);
  void on_frame(const FrameRecord& frame) override;
  void commit() override;

 private:
  std::string path_;
  size_t every_;
  StagedDirectory folder_;
  std::ofstream index_;
};

}  // namespace depot::runner
