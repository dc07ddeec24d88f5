#include "slam/detect/dnn_detector.h"

#include <unistd.h>

#include <utility>

#include "common/error.h"

#include "dataset/class_list.h"
#include "slam/detect/dnn_model.h"
#include "slam/detect/nms.h"

namespace depot::slam {

DnnDetector::DnnDetector(std::string kind, const DetectorConfig& config)
    : kind_(std::move(kind)), config_(config) {
  params_.model = config.model;
  params_.names_path = config.names;
  params_.confidence = config.confidence;
  if (config.type == "yolov5" && !config.model.empty() && ::access(config.model.c_str(), F_OK) != 0)
    fail(config.model,
         "model file not found (no YOLOv5 model ships with depot-slam: export one with "
         "ultralytics yolov5, `python export.py --weights yolov5s.pt --include onnx --imgsz 640`, "
         "and put it there, or point the detector YAML's `model` at yours)");
  require_file(config.model, "model file");
}

void DnnDetector::load(cv::Size input) {
  input_ = input;
  params_.names = dataset::load_class_names(config_.names);
  params_.wanted = wanted_classes(params_.names, config_.classes, config_.names);
  net_ = load_net();
  const cv::Mat grey(input_, CV_8UC3, cv::Scalar::all(114));
  const Input in = preprocess(grey);
  decode(run_net(net_, in.blob, config_.model), in.transform, true);
}

std::vector<Detection> DnnDetector::detect(const cv::Mat& bgr, double, long) {
  require_bgr(bgr, name());
  const Input in = preprocess(bgr);
  const std::vector<cv::Mat> outs = run_net(net_, in.blob, config_.model);
  return non_max_suppression(decode(outs, in.transform, false), config_.nms);
}

std::string DnnDetector::name() const {
  return kind_ + " (" + config_.model + ")";
}

cv::Size DnnDetector::configured_input(const DetectorConfig& config, cv::Size fallback) {
  return config.input_width > 0 ? cv::Size(config.input_width, config.input_height) : fallback;
}

DnnDetector::Input DnnDetector::stretched_input(const cv::Mat& bgr, bool swap_to_rgb) const {
  Input in;
  in.blob = cv::dnn::blobFromImage(bgr, 1 / 255.0, input_, cv::Scalar(), swap_to_rgb, false);
  in.transform.source = bgr.size();
  in.transform.target = input_;
  return in;
}

}  // namespace depot::slam
