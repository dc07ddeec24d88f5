#pragma once
// The RGB-D camera: pinhole intrinsics plus ORB-SLAM2's virtual stereo
// baseline (bf = baseline x fx), which turns a depth into a right-image
// coordinate u_r = u - bf / z so depth constrains the pose like stereo.
// Images may carry OpenCV's radial-tangential lens distortion: as in
// ORB-SLAM2, keypoints are undistorted once (slam/camera/lens_distortion.h)
// and everything after works in this undistorted pinhole, whose view of the
// image is the region [min_u, max_u) x [min_v, max_v).
#include <Eigen/Core>

#include "common/lens_model.h"

namespace depot::slam {

struct PinholeCamera {
  int width = 640;
  int height = 480;
  double fx = 535.4, fy = 539.2, cx = 320.1, cy = 247.6;
  double bf = 40.0;              // baseline (m) x fx: 0.075 m for a Kinect
  double depth_factor = 5000.0;  // depth PNG units per metre
  double close_depth = 3.0;      // m: points closer are "close" (reliable depth)
  LensCoefficients lens;         // all 0 = none
  // The undistorted image's extent (set_undistorted_bounds); used only with
  // a distortion, where it differs from the image.
  double min_u = 0, min_v = 0, max_u = 0, max_v = 0;

  bool distorted() const { return lens.any(); }

  Eigen::Vector2d project(const Eigen::Vector3d& p_cam) const {
    return {fx * p_cam.x() / p_cam.z() + cx, fy * p_cam.y() / p_cam.z() + cy};
  }
  Eigen::Vector3d unproject(double u, double v, double z) const {
    return {(u - cx) * z / fx, (v - cy) * z / fy, z};
  }
  // Whether undistorted pixel (u, v) is seen in the image.
  bool in_image(double u, double v) const {
    if (distorted()) return u >= min_u && v >= min_v && u < max_u && v < max_v;
    return u >= 0 && v >= 0 && u < width && v < height;
  }
  double right_u(double u, double z) const { return u - bf / z; }
};

}  // namespace depot::slam
