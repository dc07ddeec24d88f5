#pragma once
// The keypoints of one image with their descriptors, depths and a grid for
// fast area queries. Shared by Frame and KeyFrame.
#include <vector>

#include <opencv2/core.hpp>

#include "slam/camera/pinhole_camera.h"
#include "slam/data/scale_levels.h"

namespace depot::slam {

class Features {
 public:
  static constexpr int kGridCols = 64;
  static constexpr int kGridRows = 48;

  Features() = default;
  // Depth (CV_32F metres, 0 = none) is sampled at each keypoint; then the
  // keypoints are undistorted when the camera has a lens distortion.
  Features(std::vector<cv::KeyPoint> keypoints, cv::Mat descriptors, const cv::Mat& depth,
           const PinholeCamera& camera, const ScaleLevels* levels);
  // Depth given per keypoint (<= 0: none), as a saved map holds it
  // (keypoints already undistorted).
  Features(std::vector<cv::KeyPoint> keypoints, cv::Mat descriptors,
           std::vector<float> keypoint_depth, const PinholeCamera& camera,
           const ScaleLevels* levels);

  size_t size() const { return keypoints.size(); }
  // Indices of keypoints within radius r of (u, v) at pyramid levels
  // [min_level, max_level] (negative = no bound).
  std::vector<size_t> in_area(double u, double v, double r, int min_level = -1,
                              int max_level = -1) const;
  bool has_depth(size_t i) const { return depth[i] > 0; }

  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;         // N x 32 CV_8U
  std::vector<float> depth;    // metres, <= 0 when unknown
  std::vector<float> u_right;  // virtual right coordinate, < 0 when unknown
  // BGR colour under each keypoint (set_colours; empty when not known):
  // what a map export paints its points with.
  std::vector<cv::Vec3b> colours;
  void set_colours(const cv::Mat& bgr);  // the image's pixel under each keypoint
  const ScaleLevels* levels = nullptr;
  PinholeCamera camera;

 private:
  // u_right from depth, and the grid.
  void index();
  std::vector<std::vector<size_t>> grid_;  // row-major kGridRows x kGridCols
  double origin_u_ = 0, origin_v_ = 0;     // the grid's top-left corner
  double cell_w_ = 1, cell_h_ = 1;
};

}  // namespace depot::slam
