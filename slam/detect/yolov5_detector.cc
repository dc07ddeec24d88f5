#include "slam/detect/yolov5_detector.h"

#include "common/error.h"
#include "slam/detect/class_names.h"
#include "slam/detect/dnn_model.h"
#include "slam/detect/nms.h"

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

Yolov5Detector::Yolov5Detector(const DetectorConfig& config) : config_(config) {
  input_ = config.input_width > 0 ? cv::Size(config.input_width, config.input_height)
                                  : cv::Size(640, 640);
  params_.model = config.model;
  params_.names_path = config.names;
  params_.confidence = config.confidence;
  require_file(config.model, "model file");
  params_.names = load_class_names(config.names);
  params_.wanted = wanted_classes(params_.names, config.classes, config.names);
  net_ = load_onnx_net(config.model);
  // Warm-up on a grey frame: checks the output layout and class count now
  // rather than on the first real frame.
  const cv::Mat grey(input_, CV_8UC3, cv::Scalar::all(114));
  const cv::Mat blob = cv::dnn::blobFromImage(grey, 1 / 255.0, input_, cv::Scalar(), true, false);
  const std::vector<cv::Mat> outs = run_net(net_, blob, config.model);
  const cv::Mat& out = detection_output(outs, config.model);
  require_finite(out, config.model);
  decode_yolov5(out, params_, letterbox(grey, input_).transform);
}

std::vector<Detection> Yolov5Detector::detect(const cv::Mat& bgr, double, long) {
  require_bgr(bgr, name());
  const Letterboxed lb = letterbox(bgr, input_);
  const cv::Mat blob =
      cv::dnn::blobFromImage(lb.image, 1 / 255.0, input_, cv::Scalar(), true, false);
  const std::vector<cv::Mat> outs = run_net(net_, blob, config_.model);
  return non_max_suppression(
      decode_yolov5(detection_output(outs, config_.model), params_, lb.transform), config_.nms);
}

std::string Yolov5Detector::name() const {
  return "yolov5 (" + config_.model + ")";
}

}  // namespace depot::slam
