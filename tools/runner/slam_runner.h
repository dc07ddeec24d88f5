#pragma once
// Runs the SLAM system over one TUM folder in one rejection mode, with the
// chosen detector, and collects what `depot slam run` and the ablation
// report: trajectory, timings, rejection statistics and (for simulated
// datasets) rejection precision/recall against ground truth.
#include <memory>
#include <string>

#include "slam/detect/sim_detector_config.h"
#include "slam/io/rgbd_sequence.h"
#include "slam/reject/rejection_filter.h"
#include "slam/system/system.h"
#include "tools/runner/run_options.h"
#include "tools/runner/run_summary.h"

namespace depot::runner {

// The configuration file of a detector type when none is given: the shipped
// scenes/detectors/ YAML (sim: sim.yaml, the error model calibrated to
// Yolo-Fastest 1.1 by `depot eval calibrate`). Throws depot::Error for an
// unknown type or `file`.
std::string default_detector_config(const std::string& type);

// The simulated detector's configuration: perception.detector_config (a
// complete config over the built-in defaults of sim_detector_config.h) or
// else the shipped sim.yaml, then perception.detector_overrides, with
// perception.detector_seed as the seed.
slam::SimDetectorConfig sim_detector_config(const PerceptionChoice& perception);

// The detector `type` names (sim, file, darknet = Yolo-Fastest 1.1, xl =
// Yolo-Fastest 1.1 XL, fastestdet, yolov5), configured by
// perception.detector_config (default: default_detector_config(type); for
// sim see sim_detector_config(), on `dataset`). Throws depot::Error for an
// unknown type or a bad configuration.
std::unique_ptr<slam::Detector> make_detector(const PerceptionChoice& perception,
                                              const std::string& dataset, const std::string& type);

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

// A run's system before its first frame, for callers that feed frames
// themselves (the Python module): the settings run_sequence would use on
// `sequence` (its calibration.yaml or camera_info, then --settings and the
// run's switches), the rejection of `options`, and the system on them.
struct PreparedRun {
  slam::SlamSettings settings;
  std::string settings_source;
  RejectionSetup rejection;
  std::unique_ptr<slam::System> system;
};
PreparedRun prepare_run(const RunOptions& options, const slam::RgbdSequence& sequence);

// Tracks the dataset's frames in order; the run's outputs are written by
// frame observers (frame_observer.h). Everything is checked before the
// first frame. Throws depot::Error("<dataset>: no frame tracked: ...") when
// no frame got a pose, and then writes nothing: no map (--save-map), no
// dense cloud, none of the observers' files.
RunSummary run_sequence(const RunOptions& options);

}  // namespace depot::runner
