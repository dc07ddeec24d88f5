#include "slam/detect/person_segmenter.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>

#include <opencv2/imgproc.hpp>

#include "common/config_path.h"
#include "common/error.h"
#include "common/yaml_fields.h"
#include "common/yaml_file.h"
#include "slam/detect/decode_params.h"
#include "slam/detect/dnn_model.h"
#include "slam/detect/letterbox.h"

namespace depot::slam {
namespace {

// One of two words; `fallback` when absent.
bool read_choice(const YamlFields& fields, const char* key, const char* yes, const char* no,
                 bool fallback) {
  const std::string v = fields.str(key);
  if (v.empty()) return fallback;
  if (v != yes && v != no)
    fail(fields.where(fields.node(key)), std::string("'") + key + "' must be " + yes + " or " + no +
                                             ", not '" + printable(v) + "'");
  return v == yes;
}

// The output's one map as a rows x cols CV_32F header on its data.
cv::Mat output_map(const cv::Mat& out, const std::string& model) {
  int rows = 0, cols = 0;
  if (out.dims == 4 && out.size[0] == 1 && out.size[3] == 1) {
    rows = out.size[1];
    cols = out.size[2];
  } else if (out.dims == 4 && out.size[0] == 1 && out.size[1] == 1) {
    rows = out.size[2];
    cols = out.size[3];
  } else if (out.dims == 3 && out.size[0] == 1) {
    rows = out.size[1];
    cols = out.size[2];
  } else {
    fail(model,
         "output " + shape_string(out) + " is not one probability map (1xHxWx1, 1x1xHxW or 1xHxW)");
  }
  if (out.type() != CV_32F) fail(model, "output is not 32-bit float");
  return cv::Mat(rows, cols, CV_32F, const_cast<float*>(out.ptr<float>()));
}

}  // namespace

SegmenterConfig load_segmenter_config(const std::string& path) {
  const YAML::Node root = load_yaml_file(path, "segmenter config");
  if (!root.IsMap()) fail(path, "segmenter config must be a YAML map");
  check_known_keys(root,
                   {"model", "input_width", "input_height", "layout", "channels", "input_range",
                    "resize", "output", "threshold"},
                   path);
  const YamlFields fields(root, path, "segmenter config");
  SegmenterConfig c;
  c.model =
      resolve_config_path(fields.str("model"), std::filesystem::path(path).parent_path().string());
  if (c.model.empty()) fail(path, "missing 'model' (path of the ONNX model file)");
  c.input_width = fields.number<int>("input_width", c.input_width, 8, 4096);
  c.input_height = fields.number<int>("input_height", c.input_height, 8, 4096);
  c.nhwc = read_choice(fields, "layout", "nhwc", "nchw", c.nhwc);
  c.rgb = read_choice(fields, "channels", "rgb", "bgr", c.rgb);
  c.letterbox = read_choice(fields, "resize", "letterbox", "stretch", c.letterbox);
  c.logit = read_choice(fields, "output", "logit", "probability", c.logit);
  c.threshold = fields.number<float>("threshold", c.threshold, 0.0, 1.0);
  if (const YAML::Node range = root["input_range"]) {
    try {
      if (!range.IsSequence() || range.size() != 2) throw YAML::Exception(range.Mark(), "");
      c.input_lo = range[0].as<float>();
      c.input_hi = range[1].as<float>();
    } catch (const YAML::Exception&) {
      fail(yaml_where(path, range), "'input_range' must be two numbers [lo, hi]");
    }
    if (!(c.input_lo < c.input_hi))
      fail(yaml_where(path, range), "'input_range' must have lo < hi");
  }
  return c;
}

PersonSegmenter::PersonSegmenter(const SegmenterConfig& config)
    : config_(config), net_(load_onnx_net(config.model)) {
  const cv::Mat grey(config_.input_height, config_.input_width, CV_8UC3, cv::Scalar::all(128));
  probability(grey);
}

const cv::Mat& PersonSegmenter::probability(const cv::Mat& bgr) {
  require_bgr(bgr, name());
  const cv::Size input(config_.input_width, config_.input_height);
  cv::Rect valid(0, 0, input.width, input.height);  // the image's part of the input
  if (config_.letterbox) {
    const Letterboxed lb = letterbox(bgr, input, 0.0);
    lb.image.copyTo(sized_);
    const LetterboxTransform& t = lb.transform;
    valid = cv::Rect(static_cast<int>(t.pad_x), static_cast<int>(t.pad_y),
                     static_cast<int>(std::lround(t.source.width * t.scale)),
                     static_cast<int>(std::lround(t.source.height * t.scale)));
  } else {
    cv::resize(bgr, sized_, input, 0, 0, cv::INTER_AREA);
  }
  if (config_.rgb) cv::cvtColor(sized_, sized_, cv::COLOR_BGR2RGB);
  const double scale = (config_.input_hi - config_.input_lo) / 255.0;
  if (config_.nhwc) {
    // The NHWC blob is the HxW 3-channel float image itself.
    const int shape[] = {1, input.height, input.width, 3};
    blob_.create(4, shape, CV_32F);
    cv::Mat pixels(input.height, input.width, CV_32FC3, blob_.ptr<float>());
    sized_.convertTo(pixels, CV_32F, scale, config_.input_lo);
  } else {
    cv::dnn::blobFromImage(sized_, blob_, scale, cv::Size(), cv::Scalar(), false, false);
    if (config_.input_lo != 0.0f) blob_ += config_.input_lo;
  }
  const std::vector<cv::Mat> outs = run_net(net_, blob_, config_.model);
  cv::Mat map = output_map(outs.front(), config_.model);
  require_finite(map, config_.model);
  if (config_.logit) {
    cv::exp(-map, map);
    map = 1.0 / (1.0 + map);
  }
  // The valid region in the output's resolution, clamped there (cheap:
  // bilinear resizing keeps values in [0, 1]), then the image's size.
  const double sx = static_cast<double>(map.cols) / input.width;
  const double sy = static_cast<double>(map.rows) / input.height;
  const cv::Rect region =
      cv::Rect(cv::Point(static_cast<int>(valid.x * sx), static_cast<int>(valid.y * sy)),
               cv::Point(static_cast<int>(std::ceil(valid.br().x * sx)),
                         static_cast<int>(std::ceil(valid.br().y * sy)))) &
      cv::Rect(0, 0, map.cols, map.rows);
  cv::min(cv::max(map(region), 0.0), 1.0, clamped_);
  cv::resize(clamped_, probability_, bgr.size(), 0, 0, cv::INTER_LINEAR);
  return probability_;
}

const cv::Mat& PersonSegmenter::mask(const cv::Mat& bgr) {
  cv::compare(probability(bgr), config_.threshold, mask_, cv::CMP_GE);
  return mask_;
}

std::string PersonSegmenter::name() const {
  return "segmenter (" + config_.model + ")";
}

}  // namespace depot::slam
