#pragma once
// A frame's rejection judged against the simulator's truth, and the run's
// rejection score summed over its frames.
#include <vector>

#include "eval/motion_truth.h"
#include "slam/reject/rejection_filter.h"
#include "tools/runner/frame_observer.h"

namespace depot::runner {

struct FrameTruth {
  eval::MotionTruth::KeypointTruth labels;  // each of the filter's keypoints (MotionTruth's rule)
  eval::RejectionScore score;
  // Static keypoints rejected, by where the rejection came from: a box (Z)
  // or the flow test (Q).
  long false_positive_z = 0, false_positive_q = 0;
};

// The filter's last frame (keypoints and decisions) at `timestamp`, with the
// ORB pyramid's `scale_factor`.
FrameTruth judge_frame(const eval::MotionTruth& truth, double timestamp,
                       const slam::RejectionFilter& filter, float scale_factor);

// RunSummary::score and score_with_depth: the frames' judgements summed, the
// second over the keypoints with depth only (only they start map points).
class RejectionScoring : public FrameObserver {
 public:
  void on_frame(const FrameRecord& frame) override;
  void on_finish(const slam::System& system, const slam::RgbdSequence& sequence,
                 RunSummary& summary) override;

 private:
  eval::RejectionScore score_, score_with_depth_;
};

}  // namespace depot::runner
