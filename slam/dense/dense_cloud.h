#pragma once
// A dense point cloud of the static world, fused from keyframes' depth
// images: every pixel with depth (on a grid of `stride`) is lifted to the
// world with its keyframe's pose and falls into a voxel; each voxel becomes
// one point at the mean of its samples, with their mean colour and the
// number of keyframes that saw it. Pixels a mask marks as moving (the
// rejection's masks, or a simulated dataset's labels) are left out, grown by
// a margin because depth at an object's outline is a mix of object and
// background. What a mask missed is caught by free space (on by default):
// a voxel that keyframes see through (their depth at its pixel lies well
// behind it) or see as moving (their mask marks it) more often than they see
// it standing was something that moved. Plain data in, plain points out: the caller owns the
// images.
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "common/pose.h"
#include "slam/camera/pinhole_camera.h"
#include "slam/io/ply_file.h"

namespace depot::slam {

struct DenseCloudParams {
  float voxel_m = 0.02f;     // voxel edge
  float max_depth_m = 4.0f;  // farther depth is too noisy for a map (Kinect-like sensors)
  int stride = 2;            // every stride-th pixel of every stride-th row
  int mask_margin_px = 4;    // moving masks grown by this many pixels
  // Voxels seen from fewer keyframes are left out: one keyframe's word is
  // not enough (a mover its mask missed, depth noise at an outline).
  int min_views = 2;
  // Free space: a voxel is left out when at least as many keyframes see
  // through it or see it moving as see it standing. "Seen through": the
  // keyframe's depth at the voxel's pixel lies more than free_margin_m +
  // free_margin_per_m * depth behind it; "seen": within that of it, moving
  // when the keyframe's grown mask marks the pixel (a nearer depth hides the
  // voxel and says nothing).
  bool free_space = true;
  float free_margin_m = 0.05f;
  float free_margin_per_m = 0.02f;
};

class DenseCloud {
 public:
  // Throws depot::Error for parameters out of range.
  DenseCloud(const PinholeCamera& camera, const DenseCloudParams& params = {});

  // One keyframe: camera-to-world pose, depth (CV_32F metres, 0 = none) and
  // colour (CV_8UC3) of the camera's size, and `moving` (CV_8U, non-zero =
  // leave out; empty = nothing moves).
  void add_view(const Pose& T_wc, const cv::Mat& depth, const cv::Mat& bgr,
                const cv::Mat& moving = cv::Mat());

  // The cloud: one point per voxel seen from at least min_views keyframes,
  // in voxel order (the same views give the same bytes); count = views.
  std::vector<PlyPoint> points() const;
  int views() const { return views_; }
  size_t voxels() const { return voxels_.size(); }

 private:
  struct Voxel {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    Eigen::Vector3i colour_sum = Eigen::Vector3i::Zero();  // BGR
    int samples = 0;
    int views = 0;
    int last_view = -1;
  };

  PinholeCamera camera_;
  std::vector<cv::Point2f> undistorted_;  // per image pixel, row-major; empty without a lens
  DenseCloudParams params_;
  // What free space needs of each keyframe: its world-to-camera pose, its
  // depth and its grown moving mask (may be empty) on the stride grid.
  struct DepthView {
    Pose T_cw;
    cv::Mat depth, moving;
  };
  // Keyframes that see through the voxel at p or see it moving, and
  // keyframes that see it standing.
  std::pair<int, int> free_and_seen(const Eigen::Vector3d& p) const;

  std::unordered_map<uint64_t, Voxel> voxels_;
  std::vector<DepthView> depth_views_;
  int views_ = 0;
};

}  // namespace depot::slam
