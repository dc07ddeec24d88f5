#pragma once
// A run's outputs as observers of its frames, as stella_vslam's publishers:
// run_sequence() (slam_runner.h) is the loop that tracks the frames, and
// each observer turns what a frame gave into its own file or figures.
// Observers are owned by the run and called only from the thread that
// calls run_sequence(), in the order they were made.
#include <cstddef>
#include <vector>

#include <opencv2/core.hpp>

#include "slam/io/rgbd_sequence.h"
#include "slam/reject/rejection_filter.h"
#include "slam/system/system.h"
#include "tools/runner/run_summary.h"

namespace depot::runner {

struct FrameTruth;  // frame_truth.h

// What one tracked frame gave.
struct FrameRecord {
  size_t index;
  double timestamp;
  const cv::Mat& bgr;  // the frame's images, valid during on_frame only
  const cv::Mat& depth;
  const slam::TrackResult& result;
  const slam::RejectionFilter* filter;  // null in orb
  // The rejection's statistics (in orb: every keypoint kept, in P).
  slam::RejectionStats rejection;
  std::vector<float> keypoint_depths;  // of filter->last_keypoints() (empty without a filter)
  const FrameTruth* truth;             // the simulator's judgement (simulated data, a filter)
};

class FrameObserver {
 public:
  virtual ~FrameObserver() = default;
  // After each frame is tracked.
  virtual void on_frame(const FrameRecord& frame) = 0;
  // After the last frame, the system finished (final poses after loop
  // closing and global adjustment): what needs the final map, and the
  // observer's figures into the summary.
  virtual void on_finish(const slam::System& /*system*/, const slam::RgbdSequence& /*sequence*/,
                         RunSummary& /*summary*/) {}
  // The run succeeded (some frame got a pose): files staged so far appear.
  // A run that fails never calls it, and its staged files are removed.
  virtual void commit() {}
};

}  // namespace depot::runner
