#pragma once
// A recorded RGB-D sequence as the SLAM reads it: frames of colour, depth
// (metres) and a timestamp, from a TUM folder (tum_sequence.h) or a ROS 2
// bag (mcap_sequence.h). open_sequence() picks the reader from the path.
#include <memory>
#include <optional>
#include <string>

#include <opencv2/core.hpp>

#include "dataset/calibration.h"

namespace depot::slam {

class RgbdSequence {
 public:
  virtual ~RgbdSequence() = default;
  virtual size_t size() const = 0;
  // Frame i's time (the colour image's), seconds.
  virtual double timestamp(size_t i) const = 0;
  // Loads frame i: colour CV_8UC3 (BGR) and depth CV_32F metres (0 = none);
  // a frame that cannot be read throws depot::Error naming it.
  virtual void load(size_t i, cv::Mat& bgr, cv::Mat& depth_metres) const = 0;
  // The folder or file, for messages.
  virtual const std::string& source() const = 0;
  // Where frame i's colour image is, for errors ("<folder>/rgb/1.png",
  // "<bag> /camera/color/image_raw at 1.033333").
  virtual std::string colour_location(size_t i) const = 0;
  // A calibration.yaml beside the images ("" when there is none).
  virtual std::string calibration_path() const { return ""; }
  // The camera the recording itself states (a bag's camera_info), if any;
  // keys it does not state keep `defaults`.
  virtual std::optional<dataset::CameraCalibration> recorded_camera(
      const dataset::CameraCalibration& /*defaults*/) const {
    return std::nullopt;
  }
  // PNG depth units per metre (TUM folders); a bag's depth says its own.
  virtual void set_depth_factor(double /*factor*/) {}
};

// The topics a bag's frames are read from; empty: the defaults of
// dataset/ros2/bag_layout.h (those of the ROS 2 camera drivers).
struct BagTopics {
  std::string colour, depth, colour_info;
};

// A TUM folder, or a ROS 2 bag for a path ending in ".mcap". Throws
// depot::Error naming the path.
std::unique_ptr<RgbdSequence> open_sequence(const std::string& path, const BagTopics& topics = {});

}  // namespace depot::slam
