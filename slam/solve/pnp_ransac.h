#pragma once
// Camera pose from 2-D/3-D correspondences with RANSAC (OpenCV's EPnP inside
// RANSAC), for relocalisation.
#include <vector>

#include <Eigen/Core>

#include "common/pose.h"
#include "slam/camera/pinhole_camera.h"
#include "slam/data/features.h"

namespace depot::slam {

class MapPoint;

struct PnpResult {
  bool ok = false;
  Pose T_cw = Pose::Identity();
  std::vector<int> inliers;  // indices into the input correspondences
};

PnpResult solve_pnp_ransac(const std::vector<Eigen::Vector3d>& world_points,
                           const std::vector<Eigen::Vector2d>& pixels, const PinholeCamera& camera,
                           int iterations = 300, double max_error_px = 4.0, int min_inliers = 10);

// The same from matches: matches[i] is the map point of keypoint i of
// `features` (or null). The result's inliers are keypoint indices.
PnpResult solve_pnp_ransac(const std::vector<MapPoint*>& matches, const Features& features,
                           int iterations = 300, double max_error_px = 4.0, int min_inliers = 10);

}  // namespace depot::slam
