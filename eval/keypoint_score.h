#pragma once
// Rejection scored against a simulated dataset's truth, one rule for every
// system: the built-in modes score each frame as they run it
// (tools/runner/slam_runner.cc) and `depot eval rejection` scores any
// system's per-keypoint file (eval/keypoint_file.h) with the same call.
#include <vector>

#include <opencv2/core.hpp>

#include "eval/keypoint_file.h"
#include "eval/motion_truth.h"

namespace depot::eval {

// One frame: its keypoints classified by the truth (MotionTruth's rule at
// the pyramid's `scale_factor`) and counted by the decision `keep`.
// `labels`, when given, receives the classification.
RejectionScore score_frame(const MotionTruth& truth, double timestamp,
                           const std::vector<cv::KeyPoint>& keypoints,
                           const std::vector<uint8_t>& keep, float scale_factor,
                           MotionTruth::KeypointTruth* labels = nullptr);

struct KeypointFileScore {
  RejectionScore score;
  size_t frames = 0;     // frames with at least one row
  size_t keypoints = 0;  // rows scored
};

// Every row of the file, frame by frame (rows of a frame need not be
// together); the file's timestamps must be the truth's (read_keypoint_file
// checks them against the dataset).
KeypointFileScore score_keypoint_file(const MotionTruth& truth, const KeypointFile& file,
                                      float scale_factor);

}  // namespace depot::eval
