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

class Yolov5Detector : public Detector {
 public:
  // Loads config.model (ONNX) and config.names; input size default 640x640.
  // Runs one warm-up pass to check the output against the class list.
  // Throws depot::Error naming the offending file.
  explicit Yolov5Detector(const DetectorConfig& config);

  std::vector<Detection> detect(const cv::Mat& bgr, double timestamp, long frame_index) override;
  std::string name() const override;
  std::vector<std::string> class_names() const override { return params_.names; }

 private:
  DetectorConfig config_;
  DecodeParams params_;
  cv::Size input_;
  cv::dnn::Net net_;
};

}  // namespace depot::slam
