#pragma once
// What one SLAM run over a dataset is asked to do, by concern: the input,
// the perception models, the rejection, map reuse, the files it writes, the
// emulated camera's pace and a caller's hooks. Plain data; run_sequence()
// (slam_runner.h) checks it before any work.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "common/yaml_overrides.h"
#include "slam/dense/dense_cloud.h"
#include "slam/io/rgbd_sequence.h"
#include "slam/reject/rejection_filter.h"
#include "slam/system/system.h"
#include "slam/track/tracking_state.h"

namespace depot::runner {

struct RunInput {
  std::string dataset;           // a TUM RGB-D folder or a ROS 2 bag (.mcap)
  slam::BagTopics topics;        // a bag's colour, depth and camera_info topics
  std::optional<size_t> frames;  // only the first N
  std::string settings;          // settings YAML over the dataset's calibration.yaml ("" = none)
  std::string vocabulary;        // place-recognition vocabulary ("" = the settings' or the default)
  bool loop_closing = true;      // false: off whatever the settings say
  bool sync = false;             // local mapping in the tracking thread (reproducible)
};

// The models rejection runs on. The detector defaults to `sim` on simulated
// datasets and `darknet` otherwise (slam_runner.h make_rejection).
struct PerceptionChoice {
  std::string detector;         // sim | darknet | xl | fastestdet | yolov5 | file ("" = by dataset)
  std::string detector_config;  // YAML for dnn detectors / the simulated detector
  std::vector<YamlOverride> detector_overrides;  // simulated detector keys ("miss_rate=0.2")
  std::string detections;                        // detections file for --detector file
  std::string classes;                           // a-priori class table (default by detector)
  uint64_t detector_seed = 1;                    // the simulated detector's errors
  std::string segmenter;  // person segmenter YAML (default scenes/segmenters/selfie.yaml)
};

struct RejectionChoice {
  std::string mode = "orb";  // orb | orb+yolo | orb+lk | full | masked
  // Our extensions of full, and masked's masks, box tracking and person
  // masks (slam/reject/rejection_settings.h names each); scale_factor is set
  // from the settings by make_rejection.
  slam::RejectionParams params;
};

// Map reuse (slam/io/map_file.h): start from a saved map; only localise in
// it (needs load_map); write the map at the end.
struct MapReuse {
  std::string load_map;
  bool localise_only = false;
  std::string save_map;
};

// Files beside the trajectory, each written by a frame observer
// (frame_observer.h) and made visible only when the run succeeds.
struct RunOutputs {
  std::string stats_csv;      // per-frame statistics (stats_table.h)
  std::string keypoints_csv;  // per-keypoint sets, decisions, depth and truth (keypoint_rows.h)
  std::string overlays;       // folder of per-frame rejection pictures (rejection_overlay.h)
  size_t overlays_every = 1;  // a picture of every n-th frame
  // A dense static map written at the end as PLY ("" = none), moving pixels
  // left out by `dense_mask` (rejection | labels | none; dense_map.h).
  std::string dense_map;
  std::string dense_mask = "rejection";
  slam::DenseCloudParams dense;
};

// The input as an emulated camera whose frame i arrives at t0 + i / rate_hz
// (0 = every frame is there at once: as fast as possible).
struct CameraPacing {
  double rate_hz = 0;
  // Run-ahead: frame i+1 is handed over (System::look_ahead) before frame i
  // is tracked, so its detector runs while frame i is tracked. Frame i is
  // then tracked once frame i+1 has arrived (one frame of latency). Off:
  // frame i is tracked when it arrives and its detector starts then.
  bool run_ahead = true;
};

// A caller's hooks (each optional), e.g. a benchmark's timings and memory.
struct RunHooks {
  // In the tracking thread after each frame: its index, tracking result,
  // the rejection filter (null in orb) and the system.
  std::function<void(size_t frame, const slam::TrackResult& result,
                     const slam::RejectionFilter* filter, const slam::System& system)>
      on_frame;
  // Once after the last frame, with the system finished and the sequence,
  // before the summary is taken: e.g. to probe relocalisation with frames
  // shown again.
  std::function<void(slam::System& system, const slam::RgbdSequence& sequence)> after_run;
};

struct RunOptions {
  RunInput input;
  PerceptionChoice perception;
  RejectionChoice rejection;
  MapReuse map;
  RunOutputs outputs;
  CameraPacing pacing;
  RunHooks hooks;
  bool quiet = false;  // no progress line
};

}  // namespace depot::runner
