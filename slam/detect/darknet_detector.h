#pragma once
// Darknet YOLO (cfg + weights, e.g. Yolo-Fastest 1.1) through OpenCV dnn:
// plain resize to the input size (blobFromImage 1/255, swapRB, no crop), the
// [yolo]/[region] output layers, class-wise NMS.
#include <string>
#include <vector>

#include <opencv2/dnn.hpp>

#include "slam/detect/decode_params.h"
#include "slam/detect/detection.h"
#include "slam/detect/detector_config.h"
#include "slam/detect/dnn_detector.h"

namespace depot::slam {

// Decodes OpenCV's Darknet region outputs: each a [N, 5 + C] matrix whose rows
// are cx, cy, w, h (normalised to the image), objectness, C class scores.
// OpenCV's Region layer has already multiplied the class scores by the
// objectness, so confidence = the best class score. Rows at or below
// p.confidence or of an unwanted class are dropped; boxes go to `image`
// pixels by PAPER.md Eq. 8 (yolo_to_pixels) and are clipped to it. No NMS.
// Throws "<model>: model outputs N classes but <names> lists M".
std::vector<Detection> decode_darknet(const std::vector<cv::Mat>& outputs, const DecodeParams& p,
                                      cv::Size image);

// The [net] width x height of a Darknet cfg (0x0 if it gives none).
cv::Size darknet_cfg_input_size(const std::string& cfg);

class DarknetDetector final : public DnnDetector {
 public:
  // Loads config.config (cfg), config.model (weights) and config.names; input
  // size default: the cfg's [net] width/height. Runs one warm-up pass to check
  // the outputs against the class list. Throws depot::Error naming the file.
  explicit DarknetDetector(const DetectorConfig& config);

 private:
  cv::dnn::Net load_net() const override;
  Input preprocess(const cv::Mat& bgr) const override;
  std::vector<Detection> decode(const std::vector<cv::Mat>& outputs,
                                const LetterboxTransform& transform,
                                bool check_finite) const override;
};

}  // namespace depot::slam
