#pragma once
// What the output decoders of the dnn detectors share: the class list, the
// wanted-class filter, the confidence threshold, and the file names their
// errors cite.
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace depot::slam {

struct DecodeParams {
  std::vector<std::string> names;  // class names; index = class id
  std::vector<bool> wanted;        // per class: keep it? (empty = keep all)
  float confidence = 0.3f;         // keep detections scoring above this
  std::string model = "model";     // model file, for error messages
  std::string names_path = "class names";

  bool keeps(int class_id) const { return wanted.empty() || wanted[static_cast<size_t>(class_id)]; }
};

// Throws depot::Error "<model>: model outputs N classes but <names_path>
// lists M" unless model_classes == p.names.size().
void check_class_count(long model_classes, const DecodeParams& p);

// Throws depot::Error "<what>: expected a non-empty 8-bit 3-channel (BGR)
// image" unless `bgr` is CV_8UC3 and not empty.
void require_bgr(const cv::Mat& bgr, const std::string& what);

}  // namespace depot::slam
