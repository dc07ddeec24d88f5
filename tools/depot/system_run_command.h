#pragma once
// `depot slam run --system FILE`: another program as the SLAM system.
#include <string>

#include "eval/motion_truth.h"

namespace depot::cli {

struct SystemRunArgs {
  std::string dataset;
  std::string system;         // a system file, or a shipped system's name
  std::string output;         // TUM trajectory; states beside it
  std::string keypoints;      // "" or where to copy the system's keypoint file
  float scale_factor = 1.2f;  // the boundary rule's pyramid scale for scoring
  bool quiet = false;
};

// The system's stdout and stderr beside the trajectory: run.txt ->
// run.system.log.
std::string system_log_path(const std::string& trajectory_path);

void run_external_system(const SystemRunArgs& args);

// The one line `slam run` prints for a rejection scored against the truth
// (built-in modes and systems alike; tests read it).
void print_rejection_vs_truth(const eval::RejectionScore& score);

}  // namespace depot::cli
