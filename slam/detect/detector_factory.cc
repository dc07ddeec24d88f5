#include "slam/detect/detector_factory.h"

#include "common/error.h"
#include "slam/detect/darknet_detector.h"
#include "slam/detect/fastestdet_detector.h"
#include "slam/detect/yolov5_detector.h"

namespace depot::slam {

std::unique_ptr<Detector> make_dnn_detector(const DetectorConfig& config) {
  if (config.type == "yolov5") return std::make_unique<Yolov5Detector>(config);
  if (config.type == "darknet") return std::make_unique<DarknetDetector>(config);
  if (config.type == "fastestdet") return std::make_unique<FastestDetDetector>(config);
  fail(config.model,
       "unknown detector type '" + config.type + "' (expected yolov5, darknet or fastestdet)");
}

}  // namespace depot::slam
