#pragma once
// A ROS 2 bag (MCAP, CDR) as an RGB-D sequence: colour and depth images
// paired by their header stamps as TUM's associate.py pairs rgb.txt and
// depth.txt, the camera from the colour camera_info. Colour may be rgb8,
// bgr8 or mono8; depth 16UC1 / mono16 (millimetres, as ROS drivers publish
// it, REP 118) or 32FC1 (metres).
//
// One thread: reading a frame decompresses into the reader's chunk cache.
#include <memory>
#include <string>
#include <vector>

#include "dataset/mcap/mcap_reader.h"
#include "dataset/ros2/bag_layout.h"
#include "slam/io/rgbd_sequence.h"

namespace depot::slam {

class McapSequence : public RgbdSequence {
 public:
  // Throws depot::Error "<path>: ..." for a file that is not a readable bag,
  // a missing topic, a message type or encoding it cannot read, and colour
  // and depth streams that never come within 0.02 s of each other.
  explicit McapSequence(const std::string& path, BagTopics topics = {});

  size_t size() const override { return frames_.size(); }
  double timestamp(size_t i) const override { return frames_.at(i).timestamp; }
  void load(size_t i, cv::Mat& bgr, cv::Mat& depth_metres) const override;
  const std::string& source() const override { return path_; }
  std::string colour_location(size_t i) const override;
  std::optional<dataset::CameraCalibration> recorded_camera(
      const dataset::CameraCalibration& defaults) const override;

 private:
  struct Frame {
    double timestamp;
    mcap::MessageRef colour, depth;
  };
  std::string path_;
  BagTopics topics_;
  std::unique_ptr<mcap::Reader> reader_;
  std::vector<Frame> frames_;
  std::optional<mcap::MessageRef> camera_info_;
};

}  // namespace depot::slam
