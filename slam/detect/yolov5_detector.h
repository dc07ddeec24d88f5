#pragma once
// YOLOv5 ONNX export (ultralytics export.py --include onnx) through OpenCV
// dnn: letterbox to the input size, one forward pass, decode, class-wise NMS,
// boxes mapped back to the original image.
#include <string>
#include <vector>

#include <opencv2/dnn.hpp>

#include "slam/detect/decode_params.h"
#include "slam/detect/detection.h"
#include "slam/detect/detector_config.h"
#include "slam/detect/dnn_detector.h"
#include "slam/detect/letterbox.h"

namespace depot::slam {

// Decodes a YOLOv5 output tensor [1, N, 5 + C] (or [N, 5 + C]); each row is
// cx, cy, w, h in letterboxed input pixels, objectness, C class scores (all
// already activated by the exported graph). Per row: class = argmax of the
// class scores, confidence = objectness x that score (YOLOv5's
// non_max_suppression, multi_label off); rows at or below p.confidence or of
// an unwanted class are dropped. Boxes are mapped through `lb` back to the
// original image and clipped to it. No NMS. Throws depot::Error for a wrong
// shape or "<model>: model outputs N classes but <names> lists M".
std::vector<Detection> decode_yolov5(const cv::Mat& output, const DecodeParams& p,
                                     const LetterboxTransform& lb);

class Yolov5Detector final : public DnnDetector {
 public:
  // Loads config.model (ONNX) and config.names; input size default 640x640.
  // Runs one warm-up pass to check the output against the class list.
  // Throws depot::Error naming the offending file.
  explicit Yolov5Detector(const DetectorConfig& config);

 private:
  cv::dnn::Net load_net() const override;
  Input preprocess(const cv::Mat& bgr) const override;
  std::vector<Detection> decode(const std::vector<cv::Mat>& outputs,
                                const LetterboxTransform& transform,
                                bool check_finite) const override;
};

}  // namespace depot::slam
