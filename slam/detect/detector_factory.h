#pragma once
// Builds the OpenCV-dnn detector a DetectorConfig describes.
#include <memory>

#include "slam/detect/detection.h"
#include "slam/detect/detector_config.h"

namespace depot::slam {

// type yolov5 -> Yolov5Detector, darknet -> DarknetDetector, fastestdet ->
// FastestDetDetector. Throws one depot::Error naming the file at fault for an
// unknown type, a missing or corrupt model / cfg / names file, or a class
// list that does not match the model's outputs.
std::unique_ptr<Detector> make_dnn_detector(const DetectorConfig& config);

}  // namespace depot::slam
