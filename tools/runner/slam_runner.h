#pragma once
// Runs the SLAM system over one TUM folder in one rejection mode, with the
// chosen detector, and collects what `depot slam run` and the ablation
// report: trajectory, timings, rejection statistics and (for simulated
// datasets) rejection precision/recall against ground truth.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/tum_io.h"
#include "common/yaml_overrides.h"
#include "eval/motion_truth.h"
#include "slam/dense/dense_cloud.h"
#include "slam/detect/sim_detector_config.h"
#include "slam/io/tum_sequence.h"
#include "slam/loop/loop_closer.h"
#include "slam/reject/rejection_filter.h"
#include "slam/system/system.h"
#include "slam/track/tracking_state.h"

namespace depot::runner {

struct RunOptions {
  std::string dataset;
  std::string settings;      // optional settings YAML
  std::string vocabulary;    // place-recognition vocabulary ("" = the settings' or the default)
  bool loop_closing = true;  // false: off whatever the settings say
  // Map reuse (slam/io/map_file.h): start from a saved map; only localise
  // in it (needs load_map); write the map at the end.
  std::string load_map;
  bool localise_only = false;
  std::string save_map;
  // A dense static map (tools/runner/dense_map.h) written at the end as
  // PLY ("" = none), moving pixels left out by `dense_mask` (rejection |
  // labels | none).
  std::string dense_map;
  std::string dense_mask = "rejection";
  slam::DenseCloudParams dense;
  std::string mode = "orb";  // orb | orb+yolo | orb+lk | full | masked
  std::string detector =
      "";  // sim | darknet | xl | fastestdet | yolov5 | file ("" = sim on simulated data)
  std::string detector_config;                   // YAML for dnn detectors / the simulated detector
  std::vector<YamlOverride> detector_overrides;  // simulated detector keys ("miss_rate=0.2")
  std::string detections;                        // detections file for --detector file
  std::string classes;                           // a-priori class table (default by detector)
  uint64_t detector_seed = 1;
  std::optional<size_t> frames;
  bool sync = false;
  bool quiet = false;
  std::string stats_csv;      // per-frame statistics
  std::string keypoints_csv;  // per-keypoint sets, decisions, depth and truth
  std::string overlays;       // folder of per-frame rejection pictures (rejection_overlay.h)
  size_t overlays_every = 1;  // a picture of every n-th frame
  // The rejection's parameters (slam/reject/rejection_filter.h): our
  // extensions of full, and masked's masks, box tracking and person masks;
  // scale_factor is set from the settings by make_rejection.
  slam::RejectionParams rejection;
  std::string segmenter;  // person segmenter YAML (default scenes/segmenters/selfie.yaml)
  // The input: an emulated camera whose frame i arrives at t0 + i / rate_hz
  // (0 = every frame is there at once: as fast as possible).
  double rate_hz = 0;
  // Run-ahead: frame i+1 is handed over (System::look_ahead) before frame i
  // is tracked, so its detector runs while frame i is tracked. Frame i is
  // then tracked once frame i+1 has arrived (one frame of latency). Off:
  // frame i is tracked when it arrives and its detector starts then.
  bool run_ahead = true;
  // Per-frame recorder (optional), called in the tracking thread after each
  // frame: its index, tracking result, the rejection filter (null in orb)
  // and the system, e.g. for a benchmark's timings and memory.
  std::function<void(size_t frame, const slam::TrackResult& result,
                     const slam::RejectionFilter* filter, const slam::System& system)>
      on_frame;
  // Called once after the last frame (optional), with the system finished
  // and the sequence, before the summary is taken: e.g. to probe
  // relocalisation with frames shown again.
  std::function<void(slam::System& system, const slam::TumSequence& sequence)> after_run;
};

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

// The configuration file of a detector type when none is given: the shipped
// scenes/detectors/ YAML (sim: sim.yaml, the error model calibrated to
// Yolo-Fastest 1.1 by `depot eval calibrate`). Throws depot::Error for an
// unknown type or `file`.
std::string default_detector_config(const std::string& type);

// The simulated detector's configuration of a run: options.detector_config
// (a complete config over the built-in defaults of sim_detector_config.h)
// or else the shipped sim.yaml, then options.detector_overrides, with
// options.detector_seed as the seed.
slam::SimDetectorConfig sim_detector_config(const RunOptions& options);

// The detector `type` names (sim, file, darknet = Yolo-Fastest 1.1, xl =
// Yolo-Fastest 1.1 XL, fastestdet, yolov5), configured by
// options.detector_config (default: default_detector_config(type); for
// sim see sim_detector_config(), on options.dataset). Throws depot::Error for an unknown type or a
// bad configuration.
std::unique_ptr<slam::Detector> make_detector(const RunOptions& options, const std::string& type);

// The detector, the person segmenter (masked mode with a segmentation
// source) and the rejection filter of a run (all empty for `orb`), the
// a-priori class table checked against the detector's classes. The detector
// defaults to `sim` on simulated datasets and `darknet` otherwise.
// `scale_factor`: the ORB pyramid's (settings.orb.scale_factor).
struct RejectionSetup {
  std::unique_ptr<slam::Detector> detector;
  std::unique_ptr<slam::PersonSegmenter> segmenter;
  std::unique_ptr<slam::RejectionFilter> filter;
};
RejectionSetup make_rejection(const RunOptions& options, float scale_factor = 1.2f);

// Throws depot::Error("<dataset>: no frame tracked: ...") when no frame got
// a pose.
RunSummary run_sequence(const RunOptions& options);

}  // namespace depot::runner
