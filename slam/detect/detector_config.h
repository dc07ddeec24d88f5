#pragma once
// Configuration of an OpenCV-dnn detector, read from a small YAML file
// (scenes/detectors/*.yaml):
//
//   type: darknet            # yolov5 | darknet | fastestdet
//   model: path/to/model     # .onnx (yolov5, fastestdet) or .weights (darknet)
//   config: path/to/cfg      # darknet only
//   names: path/to/coco.names
//   input_width: 320         # optional; 0 or absent = the type's default
//   input_height: 320
//   confidence: 0.3          # optional; keep detections scoring above this
//   nms: 0.45                # optional; class-wise NMS IoU threshold
//   classes: [person, dog]   # optional; keep only these (absent/empty = all)
//
// Relative paths are resolved against the YAML file's folder.
#include <string>
#include <vector>

namespace depot::slam {

struct DetectorConfig {
  std::string type;  // yolov5 | darknet | fastestdet
  std::string model, config /* darknet cfg */, names;
  // Network input size; 0 = the type's default: yolov5 640x640, darknet the
  // cfg's [net] width/height, fastestdet 352x352.
  int input_width = 0, input_height = 0;
  float confidence = 0.3f, nms = 0.45f;
  std::vector<std::string> classes;  // keep only these; empty = all
};

// The detector types make_dnn_detector knows.
const std::vector<std::string>& dnn_detector_types();

// Reads a detector YAML (format above). Throws depot::Error
// "<yaml_path>[:line]: ..." for an unreadable file, a YAML syntax error, an
// unknown key, an unknown type, a missing required path or a value out of
// range. Model files themselves are checked by make_dnn_detector.
DetectorConfig load_detector_config(const std::string& yaml_path);

// Which of a model's class `names` to keep: all when `wanted` (the config's
// `classes`) is empty, else exactly the listed ones. Throws depot::Error
// "<names_path>: ..." for a wanted class that is not in `names`.
std::vector<bool> wanted_classes(const std::vector<std::string>& names,
                                 const std::vector<std::string>& wanted,
                                 const std::string& names_path);

}  // namespace depot::slam
