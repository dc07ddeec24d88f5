#pragma once
// Person segmentation through OpenCV dnn: a network that maps an image to a
// per-pixel person probability, e.g. MediaPipe's selfie segmentation
// (${DEPOT_SHARED_DATA}/models/selfie-segmentation: input 1x256x256x3 NHWC
// RGB in [0, 1], output 1x256x256x1 sigmoid probability). A user's own model
// loads the same way, described by a YAML file (scenes/segmenters/*.yaml):
//
//   model: path/to/model.onnx   # relative to the YAML file, or ${DEPOT_SHARED_DATA}/...
//   input_width: 256
//   input_height: 256
//   layout: nhwc          # nhwc (1xHxWx3) | nchw (1x3xHxW)
//   channels: rgb         # rgb | bgr
//   input_range: [0, 1]   # 8-bit pixel values are scaled linearly to this range
//   resize: stretch       # stretch (ignore the aspect ratio) | letterbox (pad with 0)
//   output: probability   # probability | logit (a sigmoid is applied)
//   threshold: 0.5        # mask = probability >= threshold
//
// The output must be one map (1xHxWx1, 1x1xHxW or 1xHxW) in the network
// input's geometry; it is mapped back to the image (the letterbox's padding
// removed) and resized bilinearly to the image size.
#include <string>

#include <opencv2/core.hpp>
#include <opencv2/dnn.hpp>

namespace depot::slam {

struct SegmenterConfig {
  std::string model;
  int input_width = 256, input_height = 256;
  bool nhwc = true;
  bool rgb = true;
  float input_lo = 0.0f, input_hi = 1.0f;
  bool letterbox = false;
  bool logit = false;
  float threshold = 0.5f;
};

// Reads a segmenter YAML (format above). Throws depot::Error
// "<yaml_path>[:line]: ..." for an unreadable file, a YAML error, an
// unknown key, a missing model path or a value out of range.
SegmenterConfig load_segmenter_config(const std::string& yaml_path);

class PersonSegmenter {
 public:
  // Loads the model and runs it once on a grey frame, checking that its
  // output is one finite map. Throws depot::Error naming the model file.
  explicit PersonSegmenter(const SegmenterConfig& config);

  // Person probability per pixel: CV_32F in [0, 1], the size of `bgr`
  // (CV_8UC3). The buffers are the segmenter's own, reused from frame to
  // frame (fresh ones cost several ms of page faults per frame here): the
  // result is overwritten by the next call; clone() it to keep it.
  const cv::Mat& probability(const cv::Mat& bgr);
  // probability(bgr) >= threshold: CV_8U, 255 = person; overwritten by the
  // next call like probability().
  const cv::Mat& mask(const cv::Mat& bgr);

  // "segmenter (<model file>)".
  std::string name() const;
  const SegmenterConfig& config() const { return config_; }

 private:
  SegmenterConfig config_;
  cv::dnn::Net net_;
  cv::Mat sized_, blob_, clamped_, probability_, mask_;  // per-frame buffers
};

}  // namespace depot::slam
