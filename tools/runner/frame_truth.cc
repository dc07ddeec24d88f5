#include "tools/runner/frame_truth.h"

#include "eval/keypoint_score.h"

namespace depot::runner {

FrameTruth judge_frame(const eval::MotionTruth& truth, double timestamp,
                       const slam::RejectionFilter& filter, float scale_factor) {
  FrameTruth judged;
  judged.score = eval::score_frame(truth, timestamp, filter.last_keypoints(), filter.last_keep(),
                                   scale_factor, &judged.labels);
  const std::vector<uint8_t>& moving = judged.labels.on_moving;
  for (size_t k = 0; k < moving.size(); ++k) {
    if (filter.last_keep()[k] || moving[k]) continue;
    (filter.last_sets()[k] == slam::PointSet::kZ ? judged.false_positive_z
                                                 : judged.false_positive_q)++;
  }
  return judged;
}

void RejectionScoring::on_frame(const FrameRecord& frame) {
  if (!frame.truth) return;
  score_.add(frame.truth->score);
  const eval::MotionTruth::KeypointTruth& labels = frame.truth->labels;
  const std::vector<uint8_t>& keep = frame.filter->last_keep();
  std::vector<uint8_t> keep_d, moving_d, boundary_d;
  for (size_t k = 0; k < frame.keypoint_depths.size(); ++k) {
    if (!(frame.keypoint_depths[k] > 0)) continue;
    keep_d.push_back(keep[k]);
    moving_d.push_back(labels.on_moving[k]);
    boundary_d.push_back(labels.boundary[k]);
  }
  score_with_depth_.add(keep_d, moving_d, boundary_d);
}

void RejectionScoring::on_finish(const slam::System&, const slam::RgbdSequence&,
                                 RunSummary& summary) {
  summary.score = score_;
  summary.score_with_depth = score_with_depth_;
}

}  // namespace depot::runner
