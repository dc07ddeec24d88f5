#include "slam/detect/fastestdet_detector.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "slam/detect/dnn_model.h"
#include "slam/detect/letterbox.h"

namespace depot::slam {
namespace {

float sigmoid(float x) {
  return 1.0f / (1.0f + std::exp(-x));
}

}  // namespace

std::vector<Detection> decode_fastestdet(const cv::Mat& output, const DecodeParams& p,
                                         cv::Size image) {
  if (output.type() != CV_32F || output.dims != 4 || output.size[0] != 1)
    fail(p.model,
         "unexpected output " + shape_string(output) + " (expected a float map 1x(5+classes)xHxW)");
  const long channels = 5 + static_cast<long>(p.names.size());
  // Channels first (the ONNX export) unless only the last axis fits.
  const bool channels_last = output.size[1] != channels && output.size[3] == channels;
  const int C = channels_last ? output.size[3] : output.size[1];
  const int H = channels_last ? output.size[1] : output.size[2];
  const int W = channels_last ? output.size[2] : output.size[3];
  check_class_count(static_cast<long>(C) - 5, p);
  const cv::Mat m = output.isContinuous() ? output : output.clone();
  const float* data = m.ptr<float>();
  // Element (channel c, cell h, w).
  const size_t plane = static_cast<size_t>(H) * W;
  auto at = [&](int c, int h, int w) {
    const size_t cell = static_cast<size_t>(h) * W + w;
    return channels_last ? data[cell * C + c] : data[c * plane + cell];
  };

  std::vector<Detection> dets;
  for (int h = 0; h < H; ++h) {
    for (int w = 0; w < W; ++w) {
      int best = 0;
      for (int c = 1; c < C - 5; ++c)
        if (at(5 + c, h, w) > at(5 + best, h, w)) best = c;
      const float obj = at(0, h, w), cls = at(5 + best, h, w);
      const float score = std::pow(std::max(obj, 0.0f), 0.6f) * std::pow(std::max(cls, 0.0f), 0.4f);
      if (!(score > p.confidence) || !p.keeps(best)) continue;
      const float cx = (static_cast<float>(w) + std::tanh(at(1, h, w))) / static_cast<float>(W);
      const float cy = (static_cast<float>(h) + std::tanh(at(2, h, w))) / static_cast<float>(H);
      const float bw = sigmoid(at(3, h, w)), bh = sigmoid(at(4, h, w));
      Detection d;
      d.class_id = best;
      d.class_name = p.names[static_cast<size_t>(best)];
      d.confidence = score;
      d.box = clip_box(yolo_to_pixels(cx, cy, bw, bh, image.width, image.height), image);
      if (d.box.area() > 0) dets.push_back(std::move(d));
    }
  }
  return dets;
}

FastestDetDetector::FastestDetDetector(const DetectorConfig& config)
    : DnnDetector("fastestdet", config) {
  load(configured_input(config, cv::Size(352, 352)));
}

cv::dnn::Net FastestDetDetector::load_net() const {
  return load_onnx_net(config().model);
}

DnnDetector::Input FastestDetDetector::preprocess(const cv::Mat& bgr) const {
  // FastestDet takes BGR (its examples feed OpenCV images unswapped).
  return stretched_input(bgr, /*swap_to_rgb=*/false);
}

std::vector<Detection> FastestDetDetector::decode(const std::vector<cv::Mat>& outputs,
                                                  const LetterboxTransform& transform,
                                                  bool check_finite) const {
  if (check_finite) require_finite(outputs.front(), config().model);
  return decode_fastestdet(outputs.front(), params(), transform.source);
}

}  // namespace depot::slam
