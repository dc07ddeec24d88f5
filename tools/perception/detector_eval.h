#pragma once
// Runs a detector over the frames of a simulated dataset (against its
// boxes.txt) or over hand-labelled images, and scores it (eval/
// detection_score.h): what `depot eval detector` and the tests share.
#include <functional>
#include <string>
#include <vector>

#include "eval/class_mapping.h"
#include "eval/detection_report.h"
#include "eval/detection_score.h"
#include "eval/image_labels.h"
#include "eval/instance_classes.h"
#include "slam/detect/detection.h"
#include "slam/detect/truth_boxes.h"

namespace depot::perception {

struct DetectorEval {
  eval::DetectionScore score;
  std::string detector;             // its name
  std::vector<std::string> labels;  // its class names
  std::vector<double> detect_ms;    // per scored frame

  // The side of a report, named `name`.
  eval::DetectionSide side(const std::string& name) const;
};

// The class mapping of a detector type: the identity for `sim` (its labels
// are the simulator's classes), else `path` or, when empty, the shipped
// scenes/detectors/coco_to_depot.yaml.
eval::ClassMapping class_mapping_for(const std::string& type, const std::string& path);

// The truth boxes as the scoring takes them; `assets` (instance id -> the
// catalogue asset it is drawn from) names each box's model.
std::vector<eval::TruthObject> truth_objects(const std::vector<slam::TruthBox>& boxes,
                                             const std::map<int, std::string>& assets = {});

// Sees every scored frame of a dataset: its rgb.txt index, its truth boxes
// (boxes.txt order) and the detections scored against them.
using FrameObserver = std::function<void(size_t frame, const std::vector<slam::TruthBox>& truth,
                                         const std::vector<eval::ScoredDetection>& detections)>;

// Scores `detector` on frames 0, every, 2 every, ... of `dataset`. The
// mapping's classes must be classes of the dataset (classes.txt). With
// `reads_pixels` false the frames are not loaded (the simulated detector
// reads only boxes.txt). `observe`, when given, sees every scored frame
// (`depot eval calibrate` collects its samples so). Throws depot::Error
// naming the file at fault.
DetectorEval evaluate_on_dataset(slam::Detector& detector, const std::string& dataset,
                                 const eval::ClassMapping& mapping, size_t every, bool reads_pixels,
                                 bool quiet, const FrameObserver& observe = {});

// Scores `detector` on the images of a labels file (eval/image_labels.h).
DetectorEval evaluate_on_images(slam::Detector& detector, const eval::ImageLabels& labels,
                                const eval::ClassMapping& mapping, bool quiet);

}  // namespace depot::perception
