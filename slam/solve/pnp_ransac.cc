#include "slam/solve/pnp_ransac.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

#include "slam/data/map_point.h"

namespace depot::slam {

PnpResult solve_pnp_ransac(const std::vector<Eigen::Vector3d>& world_points,
                           const std::vector<Eigen::Vector2d>& pixels, const PinholeCamera& camera,
                           int iterations, double max_error_px, int min_inliers) {
  PnpResult result;
  if (world_points.size() < 6 || world_points.size() != pixels.size()) return result;
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> image;
  for (size_t i = 0; i < world_points.size(); ++i) {
    object.emplace_back(world_points[i].x(), world_points[i].y(), world_points[i].z());
    image.emplace_back(pixels[i].x(), pixels[i].y());
  }
  cv::Mat K = (cv::Mat_<double>(3, 3) << camera.fx, 0, camera.cx, 0, camera.fy, camera.cy, 0, 0, 1);
  cv::Mat rvec, tvec;
  std::vector<int> inliers;
  // A fixed RNG state keeps relocalisation deterministic.
  cv::theRNG().state = 0x12345678;
  if (!cv::solvePnPRansac(object, image, K, cv::noArray(), rvec, tvec, false, iterations,
                          max_error_px, 0.99, inliers, cv::SOLVEPNP_EPNP))
    return result;
  if (static_cast<int>(inliers.size()) < min_inliers) return result;
  cv::Mat R;
  cv::Rodrigues(rvec, R);
  Eigen::Matrix3d r;
  Eigen::Vector3d t;
  cv::cv2eigen(R, r);
  cv::cv2eigen(tvec, t);
  result.ok = true;
  result.T_cw = make_pose(r, t);
  result.inliers = inliers;
  return result;
}

PnpResult solve_pnp_ransac(const std::vector<MapPoint*>& matches, const Features& features,
                           int iterations, double max_error_px, int min_inliers) {
  std::vector<Eigen::Vector3d> world;
  std::vector<Eigen::Vector2d> pixels;
  std::vector<size_t> keypoint;
  for (size_t i = 0; i < matches.size(); ++i) {
    if (!matches[i]) continue;
    world.push_back(matches[i]->position);
    pixels.emplace_back(features.keypoints[i].pt.x, features.keypoints[i].pt.y);
    keypoint.push_back(i);
  }
  PnpResult result =
      solve_pnp_ransac(world, pixels, features.camera, iterations, max_error_px, min_inliers);
  for (int& k : result.inliers) k = static_cast<int>(keypoint[k]);
  return result;
}

}  // namespace depot::slam
