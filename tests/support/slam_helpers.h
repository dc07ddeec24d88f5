#pragma once
// Runs the real SLAM system over a rendered dataset in one rejection mode
// and scores it against the simulator's ground truth.
#include <string>

#include "eval/motion_truth.h"
#include "slam/reject/rejection_filter.h"

namespace depot::test {

struct SlamOutcome {
  double ate_rmse = 0;  // over the tracked frames only
  eval::RejectionScore score;
  int lost = 0;
  size_t frames = 0;           // frames given
  size_t tracked = 0;          // frames with a pose (System::frame_states)
  size_t trajectory_size = 0;  // == tracked
  double tracked_share() const { return frames ? static_cast<double>(tracked) / frames : 0.0; }
};

// The simulated detector as `--detector sim` has it by default (the shipped
// scenes/detectors/sim.yaml, calibrated to Yolo-Fastest 1.1) and the depot
// class table; `threaded` picks the mapping thread (false = reproducible).
SlamOutcome run_slam_mode(const std::string& dataset, slam::RejectionMode mode, bool threaded,
                          const slam::RejectionParams& params = {});

}  // namespace depot::test
