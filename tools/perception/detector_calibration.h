#pragma once
// Calibrating the simulated detector to a real one (`depot eval calibrate`):
// the real detector runs over simulated datasets (evaluate_on_dataset, the
// same loop, matching and class mapping as `depot eval detector`), every
// ground-truth box becomes a sample of what the detector did with it, the
// simulated detector's error model is fitted to the samples
// (tools/perception/sim_detector_fit.h), and the fitted simulated detector is
// re-run on the same datasets so that its recall per class can be compared
// with the real one's.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "dataset/dataset_info.h"
#include "eval/class_mapping.h"
#include "eval/detection_score.h"
#include "slam/detect/detection.h"
#include "slam/detect/sim_detector_config.h"
#include "tools/perception/sim_detector_fit.h"

namespace depot::perception {

struct CalibrationRequest {
  std::vector<std::string> datasets;  // simulated dataset folders
  size_t every = 1;                   // score frames 0, every, 2 every, ...
  eval::ClassMapping mapping;         // the detector's labels -> the simulator's classes
  double min_confidence = 0.3;        // the detector's threshold
  // Kept keys (default_fill, latency_frames) and the occlusion reference.
  slam::SimDetectorConfig base;
  bool reads_pixels = true;  // false for the simulated detector itself
  int sim_seeds = 10;        // seeds of the fitted simulated detector's re-run
  bool quiet = false;
};

struct CalibrationDataset {
  std::string path;
  std::optional<dataset::DatasetInfo> info;  // its info.json (none when absent)
  cv::Size image_size;
  size_t frames = 0, scored_frames = 0;
};

struct ClassCalibration {
  long truth_boxes = 0;
  long detections = 0;               // the real detector's detections counted as this class
  eval::Tally real_all, real_clear;  // recall of the real detector
  eval::Tally sim_all, sim_clear;    // of the fitted simulated detector, over sim_seeds seeds
};

struct DetectorCalibration {
  SimDetectorFit fit;
  std::vector<CalibrationDataset> datasets;
  std::vector<std::string> classes;  // the datasets' classes.txt classes, in order
  std::map<std::string, ClassCalibration> per_class;
  long real_false_positives = 0, sim_false_positives = 0;  // as `eval detector` counts them
  long sim_frames = 0;                                     // over all seeds
  int sim_seeds = 0;
  std::string detector_name;
};

// Throws depot::Error naming `path` unless it is a folder with boxes.txt.
void check_calibration_dataset(const std::string& path);

// Checks every dataset (a folder with boxes.txt that the simulated detector
// reads, classes the mapping knows) before the first frame, runs, fits and
// re-runs. `config_text` receives the fitted keys as YAML, exactly as the
// re-run used them. Throws depot::Error naming the dataset or the problem
// (e.g. no box matched: nothing to fit jitter on).
DetectorCalibration calibrate_sim_detector(slam::Detector& detector,
                                           const CalibrationRequest& request,
                                           std::string& config_text);

// What the calibration file records about its measurement.
struct CalibrationMeta {
  std::string detector_type;  // darknet, xl, ...
  std::string detector_config, class_map;
  size_t every = 1;
  std::string command;  // the command line that regenerates the file
};

// The whole calibration file: a header comment, the fitted keys
// (`config_text`) and the `calibration:` block.
std::string calibration_file_text(const DetectorCalibration& calibration,
                                  const std::string& config_text, const CalibrationMeta& meta);

// A path as the calibration file records it: relative to the project
// (scenes/...) or ${DEPOT_SHARED_DATA}/... when inside them, else as given.
std::string portable_path(const std::string& path);

}  // namespace depot::perception
