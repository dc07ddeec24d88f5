#pragma once
// FastestDet (dog-qiuqiu/FastestDet, ONNX) through OpenCV dnn: plain resize
// to the input size (BGR, 1/255), one grid output map, class-wise NMS.
#include <string>
#include <vector>

#include <opencv2/dnn.hpp>

#include "slam/detect/decode_params.h"
#include "slam/detect/detection.h"
#include "slam/detect/detector_config.h"
#include "slam/detect/dnn_detector.h"

namespace depot::slam {

// Decodes FastestDet's output map [1, 5 + C, H, W] (or channels-last
// [1, H, W, 5 + C]). Per grid cell (row h, column w) the channels are:
// objectness (sigmoid already applied in the graph), box regression tx, ty,
// tw, th (raw), C class scores (softmax already applied). As FastestDet's own
// C++ example (example/ncnn/FastestDet.cpp) does:
//   class = argmax of the class scores, score = obj^0.6 * cls^0.4,
//   cx = (w + tanh(tx)) / W, cy = (h + tanh(ty)) / H,
//   bw = sigmoid(tw), bh = sigmoid(th)   (all normalised to the image),
// then PAPER.md Eq. 8 (yolo_to_pixels) to `image` pixels, clipped. Cells
// scoring at or below p.confidence or of an unwanted class are dropped. No
// NMS. Throws "<model>: model outputs N classes but <names> lists M".
std::vector<Detection> decode_fastestdet(const cv::Mat& output, const DecodeParams& p,
                                         cv::Size image);

class FastestDetDetector final : public DnnDetector {
 public:
  // Loads config.model (ONNX) and config.names; input size default 352x352.
  // Runs one warm-up pass to check the output against the class list.
  // Throws depot::Error naming the offending file.
  explicit FastestDetDetector(const DetectorConfig& config);

 private:
  cv::dnn::Net load_net() const override;
  Input preprocess(const cv::Mat& bgr) const override;
  std::vector<Detection> decode(const std::vector<cv::Mat>& outputs,
                                const LetterboxTransform& transform,
                                bool check_finite) const override;
};

}  // namespace depot::slam
