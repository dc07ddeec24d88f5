#pragma once
// A TUM RGB-D folder (real or simulated) as a sequence of (rgb, depth,
// timestamp). Uses associations.txt when present, otherwise associates
// rgb.txt with depth.txt as TUM's associate.py does.
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "common/tum_io.h"
#include "slam/io/rgbd_sequence.h"

namespace depot::slam {

class TumSequence : public RgbdSequence {
 public:
  // Fails (depot::Error naming the file) when the folder or its lists are
  // missing, empty or share no timestamps.
  explicit TumSequence(const std::string& folder, double depth_factor = 5000.0);

  size_t size() const override { return frames_.size(); }
  double timestamp(size_t i) const override { return frames_.at(i).rgb_timestamp; }
  const Association& entry(size_t i) const { return frames_[i]; }
  const std::string& folder() const { return folder_; }
  const std::string& source() const override { return folder_; }
  std::string colour_location(size_t i) const override;
  // The calibration.yaml beside the images, or "" when there is none.
  std::string calibration_path() const override;
  // Missing or unreadable images and depth that is not 16-bit throw.
  void load(size_t i, cv::Mat& bgr, cv::Mat& depth_metres) const override;
  void set_depth_factor(double f) override { depth_factor_ = f; }

 private:
  std::string folder_;
  double depth_factor_;
  std::vector<Association> frames_;
};

}  // namespace depot::slam
