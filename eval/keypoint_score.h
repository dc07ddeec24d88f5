#pragma once
// Rejection scored against a simulated dataset's truth, one rule for every
// system: the built-in modes score each frame as they run it
// (tools/runner/slam_runner.cc) and `depot eval rejection` scores any
// system's per-keypoint file (eval/keypoint_file.h) with the same call.
#include <cmath>
#include <map>
#include <string>
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

// Keypoints on movers of one class: how many, and how many were rejected.
struct ClassRecall {
  long moving = 0;
  long rejected = 0;
  double recall() const { return moving ? static_cast<double>(rejected) / moving : NAN; }
};

struct KeypointFileScore {
  RejectionScore score;
  // Recall by the class of the moving object a keypoint lies on (objects.json):
  // whether a mover of an a-priori static class (a carried crate) is
  // rejected, beside the people. Empty when the dataset has no objects.json.
  std::map<std::string, ClassRecall> moving_by_class;
  size_t frames = 0;          // frames with at least one row
  size_t keypoints = 0;       // rows scored
  size_t dataset_frames = 0;  // frames the dataset's labels list (score_dataset_keypoints)
  bool has_octave = false;    // the file had an octave column (score_dataset_keypoints)
};

// Every row of the file, frame by frame (rows of a frame need not be
// together); the file's timestamps must be the truth's (read_keypoint_file
// checks them against the dataset).
KeypointFileScore score_keypoint_file(const MotionTruth& truth, const KeypointFile& file,
                                      float scale_factor);

// A per-keypoint file scored against a simulated dataset's labels: the
// dataset's truth loaded, the file read and checked against its frames and
// image size, then score_keypoint_file. Throws depot::Error (one line) for a
// dataset without labels and for every problem of the file.
KeypointFileScore score_dataset_keypoints(const std::string& dataset,
                                          const std::string& keypoints_path, float scale_factor);

}  // namespace depot::eval
