#pragma once
// A rigid transform (no scale: RGB-D measures it) from 3-D/3-D
// correspondences with RANSAC, for loop closing: T maps points of frame B
// into frame A. Minimal samples of three pairs are solved in closed form
// (Umeyama, Eigen::umeyama without scaling); a pair is an inlier when its
// point of B lands within `max_error_px` of its pixel in camera A and its
// point of A lands within it of its pixel in camera B.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "common/pose.h"
#include "slam/camera/pinhole_camera.h"

namespace depot::slam {

struct RigidCorrespondence {
  Eigen::Vector3d in_a, in_b;  // the point in camera A and in frame B
  Eigen::Vector2d pixel_a, pixel_b;
  Pose T_b_camera = Pose::Identity();  // frame B -> camera that saw pixel_b
  double max_error_px = 4.0;           // per pair: grows with the keypoints' scale
};

struct RigidResult {
  bool ok = false;
  Pose T_ab = Pose::Identity();
  std::vector<int> inliers;
};

RigidResult solve_rigid_ransac(const std::vector<RigidCorrespondence>& pairs,
                               const PinholeCamera& camera, int iterations = 300,
                               int min_inliers = 20, uint64_t seed = 1);

}  // namespace depot::slam
