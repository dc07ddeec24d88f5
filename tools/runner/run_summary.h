#pragma once
// What one SLAM run over a dataset gave (run_sequence(), slam_runner.h):
// trajectories, frame states, timings, loops and the atlas, rejection scores
// and the dense map's size.
#include <cstddef>
#include <string>
#include <vector>

#include "common/tum_io.h"
#include "eval/motion_truth.h"
#include "slam/loop/loop_closer.h"
#include "slam/track/tracking_state.h"

namespace depot::runner {

// The problem run_sequence() names when no frame got a pose (an outcome a
// sweep records, not a crash).
inline constexpr const char* kNoFrameTracked = "no frame tracked";

struct RunSummary {
  size_t frames = 0;              // frames given to the system
  size_t tracked = 0;             // of them, with a pose in the trajectory
  int lost = 0, relocalized = 0;  // frames tracking reported lost / relocalised
  size_t keyframes = 0, map_points = 0;
  double median_ms = 0, p95_ms = 0, extract_ms = 0, track_ms = 0;
  double filter_ms = 0, wait_ms = 0, detect_ms = 0, flow_ms = 0;  // medians
  double wait_p95_ms = 0;
  double lost_ms = 0;  // median time of a frame tracked while lost (relocalisation tries)
  std::vector<slam::LoopClosure> loops;
  int loops_refused = 0;       // look-alike places refused by the plausibility test
  int global_adjustments = 0;  // global bundle adjustments applied after loops
  int maps = 0;                // maps left in the atlas (slam/data/map.h)
  int merges_unconfirmed = 0;  // merges the keyframe's neighbours did not confirm
  int maps_rejoined = 0;       // young maps merged by a relocalised frame
  // With rate_hz: frames whose turn (the arrival of frame i, or of frame i+1
  // with run-ahead) had passed when the loop got to them: the tracker lagged.
  size_t late_frames = 0;
  double ba_ms_total = 0;
  size_t dense_points = 0;  // points of the dense map (with dense_map)
  int dense_keyframes = 0;  // keyframes fused into it
  int dense_left_out = 0;   // keyframes left out: a loaded map's, no frame or no mask of this run
  // The dense maps of the atlas's other maps (map 1, 2, ... as in
  // frame_states), each in its own map's frame beside the main one.
  struct DenseMapFile {
    int map = 0;
    std::string path;    // empty when the map gave no dense map
    std::string reason;  // why not, then
    size_t points = 0;
    int keyframes = 0;
  };
  std::vector<DenseMapFile> dense_other_maps;
  std::vector<StampedPose> trajectory;                // the tracked frames only
  std::vector<slam::StampedFrameState> frame_states;  // every frame given, with its map
  // Every frame with a pose, each in its atlas map's frame (the frames of
  // frame_states with a map, in order; slam/io/frame_states_file.h).
  std::vector<StampedPose> atlas_trajectory;
  std::vector<StampedPose> keyframes_trajectory;
  bool scored = false;
  eval::RejectionScore score;  // with the boundary class (MotionTruth)
  // The same over the keypoints with depth, the ones that can start map
  // points (RGB-D ORB-SLAM2 makes none from a keypoint without depth).
  eval::RejectionScore score_with_depth;
  std::string settings_source;
  std::string detector_name;

  // Tracked frames / frames given.
  double tracked_share() const { return frames ? static_cast<double>(tracked) / frames : 0.0; }
};

}  // namespace depot::runner
