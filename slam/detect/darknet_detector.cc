#include "slam/detect/darknet_detector.h"

#include <fstream>

#include "common/error.h"
#include "slam/detect/dnn_model.h"
#include "slam/detect/letterbox.h"

namespace depot::slam {

std::vector<Detection> decode_darknet(const std::vector<cv::Mat>& outputs, const DecodeParams& p,
                                      cv::Size image) {
  std::vector<Detection> dets;
  for (const cv::Mat& out : outputs) {
    if (out.type() != CV_32F || out.dims != 2)
      fail(p.model, "unexpected output " + shape_string(out) +
                        " (expected a float matrix Nx(5+classes) from a [yolo]/[region] layer)");
    check_class_count(static_cast<long>(out.cols) - 5, p);
    for (int r = 0; r < out.rows; ++r) {
      const float* row = out.ptr<float>(r);
      int best = 0;
      for (int c = 1; c < out.cols - 5; ++c)
        if (row[5 + c] > row[5 + best]) best = c;
      const float conf = row[5 + best];
      if (!(conf > p.confidence) || !p.keeps(best)) continue;
      Detection d;
      d.class_id = best;
      d.class_name = p.names[static_cast<size_t>(best)];
      d.confidence = conf;
      d.box = clip_box(yolo_to_pixels(row[0], row[1], row[2], row[3], image.width, image.height),
                       image);
      if (d.box.area() > 0) dets.push_back(std::move(d));
    }
  }
  return dets;
}

cv::Size darknet_cfg_input_size(const std::string& cfg) {
  std::ifstream in(cfg);
  if (!in) fail(cfg, "cannot open Darknet cfg file");
  cv::Size size(0, 0);
  bool in_net = false;
  for (std::string line; std::getline(in, line);) {
    std::string s;
    for (char ch : line)
      if (ch != ' ' && ch != '\t' && ch != '\r') s += ch;
    if (s.empty() || s[0] == '#' || s[0] == ';') continue;
    if (s[0] == '[') {
      if (in_net) break;  // [net] is over
      in_net = s == "[net]" || s == "[network]";
      continue;
    }
    if (!in_net) continue;
    try {
      if (s.rfind("width=", 0) == 0) size.width = std::stoi(s.substr(6));
      if (s.rfind("height=", 0) == 0) size.height = std::stoi(s.substr(7));
    } catch (const std::exception&) {
      fail(cfg, "bad [net] size line '" + line + "'");
    }
  }
  return size;
}

DarknetDetector::DarknetDetector(const DetectorConfig& config) : DnnDetector("darknet", config) {
  require_file(config.config, "Darknet cfg file");
  cv::Size input;
  if (config.input_width > 0) {
    input = cv::Size(config.input_width, config.input_height);
  } else {
    input = darknet_cfg_input_size(config.config);
    if (input.width <= 0 || input.height <= 0)
      fail(config.config, "no [net] width/height: give input_width and input_height");
  }
  load(input);
}

cv::dnn::Net DarknetDetector::load_net() const {
  return load_darknet_net(config().config, config().model);
}

DnnDetector::Input DarknetDetector::preprocess(const cv::Mat& bgr) const {
  return stretched_input(bgr, /*swap_to_rgb=*/true);
}

std::vector<Detection> DarknetDetector::decode(const std::vector<cv::Mat>& outputs,
                                               const LetterboxTransform& transform,
                                               bool check_finite) const {
  if (check_finite)
    for (const cv::Mat& out : outputs) require_finite(out, config().model);
  return decode_darknet(outputs, params(), transform.source);
}

}  // namespace depot::slam
