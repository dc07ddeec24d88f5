#include "slam/detect/decode_params.h"

#include "common/error.h"

namespace depot::slam {

void check_class_count(long model_classes, const DecodeParams& p) {
  if (model_classes < 1) fail(p.model, "model output has no class scores (not a YOLO-style head)");
  if (model_classes != static_cast<long>(p.names.size()))
    fail(p.model, "model outputs " + std::to_string(model_classes) + " classes but " +
                      p.names_path + " lists " + std::to_string(p.names.size()));
}

void require_bgr(const cv::Mat& bgr, const std::string& what) {
  if (bgr.empty() || bgr.type() != CV_8UC3)
    fail(what, "expected a non-empty 8-bit 3-channel (BGR) image");
}

}  // namespace depot::slam
