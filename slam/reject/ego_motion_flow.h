#pragma once
// Our extension of the paper's flow test (off by default): instead of
// comparing a point's LK flow with P's mean flow (Eq. 6-7), compare it with
// the flow the camera's own motion would give a static point at that depth.
// The motion between the previous and the current frame is fitted to the
// reference (P) points by PnP RANSAC on their depth and flow. A static point
// at any depth then agrees to within LK noise, however the camera moves,
// where the mean flow differs from a static point's flow by the parallax and
// rotation across the image.
#include <vector>

#include <opencv2/core.hpp>

#include "slam/camera/pinhole_camera.h"

namespace depot::slam {

struct EgoMotionParams {
  float threshold_px = 2.0f;      // residual above which a point moves (at 640 px width)
  float ransac_px = 1.5f;         // PnP RANSAC inlier threshold (at 640 px width)
  int min_points = 12;            // reference points with depth needed for a fit
  float min_inlier_share = 0.5f;  // of those; fewer means no trustworthy fit
  // A point without depth is beyond the sensor's range (or at an edge): it
  // is tested as lying anywhere from this depth (m) to infinity.
  float no_depth_min = 4.0f;
  // Guided re-tracking of tested points from their predicted position.
  int refine_window = 9;           // px
  int refine_levels = 1;           // pyramid levels above the full image
  float refine_max_error = 12.0f;  // LK mean abs difference (grey levels)
};

struct EgoMotionModel {
  bool valid = false;
  cv::Matx33d rotation = cv::Matx33d::eye();  // current camera -> previous camera
  cv::Vec3d translation{0, 0, 0};
  int points = 0, inliers = 0;
};

// Fits the motion from reference points: current pixel, depth (m, <= 0 =
// none), LK flow (previous pixel = current - flow) and whether it tracked.
EgoMotionModel fit_ego_motion(const PinholeCamera& camera, const std::vector<cv::Point2f>& pixels,
                              const std::vector<float>& depth, const std::vector<cv::Point2f>& flow,
                              const std::vector<uint8_t>& ok, const EgoMotionParams& params);

// Where a static point seen at `pixel` was in the previous frame: at its
// depth, or for no depth the ends of the segment from `no_depth_min` to
// infinity (near == far with depth). False without a model or behind the
// camera.
bool predict_static_previous(const EgoMotionModel& model, const PinholeCamera& camera,
                             const cv::Point2f& pixel, float depth, float no_depth_min,
                             cv::Point2f* near, cv::Point2f* far);

// Distance (px) from an observed previous position to the predicted segment.
float distance_to_prediction(const cv::Point2f& seen, const cv::Point2f& near,
                             const cv::Point2f& far);

// The threshold scaled to the image width (the defaults are for 640 px).
inline float scaled_px(float px_at_640, const PinholeCamera& camera) {
  return px_at_640 * static_cast<float>(camera.width) / 640.0f;
}

}  // namespace depot::slam
