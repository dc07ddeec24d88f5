#pragma once
// What the OpenCV-dnn detectors (YOLOv5, Darknet, FastestDet) share: the
// class names and wanted-class filter, model loading, one warm-up pass, and
// the preprocess -> run -> decode -> class-wise NMS flow. Each detector adds
// only its own preprocessing and output decoding.
#include <string>
#include <vector>

#include <opencv2/dnn.hpp>

#include "slam/detect/decode_params.h"
#include "slam/detect/detection.h"
#include "slam/detect/detector_config.h"
#include "slam/detect/letterbox.h"

namespace depot::slam {

class DnnDetector : public Detector {
 public:
  std::vector<Detection> detect(const cv::Mat& bgr, double timestamp, long frame_index) final;
  // "<kind> (<model file>)".
  std::string name() const final;
  std::vector<std::string> class_names() const final { return params_.names; }

 protected:
  // One frame as the network takes it, and how its boxes map back to the
  // frame (a plain resize fills in only transform.source and .target).
  struct Input {
    cv::Mat blob;
    LetterboxTransform transform;
  };

  // Takes the decode parameters from `config` and checks that its model file
  // exists; `kind` names the detector in name().
  DnnDetector(std::string kind, const DetectorConfig& config);

  // The second stage of construction, for the derived constructor to call
  // once it knows the input size: loads the class names, then the network
  // (load_net), and runs one warm-up pass on a grey input-sized frame that
  // checks the outputs (finite values, layout, class count) now rather than
  // on the first real frame. Throws depot::Error naming the file at fault.
  void load(cv::Size input);

  // The network, read from the configured files.
  virtual cv::dnn::Net load_net() const = 0;
  // A BGR frame as the network input.
  virtual Input preprocess(const cv::Mat& bgr) const = 0;
  // The outputs as frame detections, before NMS. With `check_finite` (the
  // warm-up) the outputs it reads must be finite first.
  virtual std::vector<Detection> decode(const std::vector<cv::Mat>& outputs,
                                        const LetterboxTransform& transform,
                                        bool check_finite) const = 0;

  // The frame stretched to the input size, scaled to [0, 1] (no letterbox),
  // channels swapped to RGB when the model wants it.
  Input stretched_input(const cv::Mat& bgr, bool swap_to_rgb) const;

  // config.input_width x input_height when given, else `fallback`.
  static cv::Size configured_input(const DetectorConfig& config, cv::Size fallback);

  const DetectorConfig& config() const { return config_; }
  const DecodeParams& params() const { return params_; }
  cv::Size input() const { return input_; }

 private:
  std::string kind_;
  DetectorConfig config_;
  DecodeParams params_;
  cv::Size input_;
  cv::dnn::Net net_;
};

}  // namespace depot::slam
