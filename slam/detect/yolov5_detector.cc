#include "slam/detect/yolov5_detector.h"

#include "common/error.h"
#include "slam/detect/dnn_model.h"

namespace depot::slam {
namespace {

// The [1, N, 5 + C] detection output among the unconnected outputs (older
// exports also expose the three raw [1, 3, H, W, 5 + C] heads).
const cv::Mat& detection_output(const std::vector<cv::Mat>& outs, const std::string& model) {
  for (const cv::Mat& m : outs)
    if (m.dims == 3 || m.dims == 2) return m;
  std::string shapes;
  for (const cv::Mat& m : outs) shapes += (shapes.empty() ? "" : ", ") + shape_string(m);
  fail(model, "no YOLOv5 detection output (expected 1xNx(5+classes), got " + shapes + ")");
}

}  // namespace

std::vector<Detection> decode_yolov5(const cv::Mat& output, const DecodeParams& p,
                                     const LetterboxTransform& lb) {
  if (output.type() != CV_32F || !((output.dims == 3 && output.size[0] == 1) || output.dims == 2))
    fail(p.model, "unexpected output " + shape_string(output) +
                      " (expected a float tensor 1xNx(5+classes))");
  const int rows = output.size[output.dims - 2];
  const int cols = output.size[output.dims - 1];
  check_class_count(static_cast<long>(cols) - 5, p);
  const cv::Mat m = output.isContinuous() ? output : output.clone();
  const float* data = m.ptr<float>();

  std::vector<Detection> dets;
  for (int r = 0; r < rows; ++r) {
    const float* row = data + static_cast<size_t>(r) * cols;
    const float obj = row[4];
    if (!(obj > p.confidence)) continue;  // conf = obj x cls <= obj
    int best = 0;
    for (int c = 1; c < cols - 5; ++c)
      if (row[5 + c] > row[5 + best]) best = c;
    const float conf = obj * row[5 + best];
    if (!(conf > p.confidence) || !p.keeps(best)) continue;
    const cv::Rect2f in_input(row[0] - row[2] / 2, row[1] - row[3] / 2, row[2], row[3]);
    Detection d;
    d.class_id = best;
    d.class_name = p.names[static_cast<size_t>(best)];
    d.confidence = conf;
    d.box = clip_box(from_letterbox(in_input, lb), lb.source);
    if (d.box.area() > 0) dets.push_back(std::move(d));
  }
  return dets;
}

Yolov5Detector::Yolov5Detector(const DetectorConfig& config) : DnnDetector("yolov5", config) {
  load(configured_input(config, cv::Size(640, 640)));
}

cv::dnn::Net Yolov5Detector::load_net() const {
  return load_onnx_net(config().model);
}

DnnDetector::Input Yolov5Detector::preprocess(const cv::Mat& bgr) const {
  const Letterboxed lb = letterbox(bgr, input());
  return {cv::dnn::blobFromImage(lb.image, 1 / 255.0, input(), cv::Scalar(), true, false),
          lb.transform};
}

std::vector<Detection> Yolov5Detector::decode(const std::vector<cv::Mat>& outputs,
                                              const LetterboxTransform& transform,
                                              bool check_finite) const {
  const cv::Mat& out = detection_output(outputs, config().model);
  if (check_finite) require_finite(out, config().model);
  return decode_yolov5(out, params(), transform);
}

}  // namespace depot::slam
