#pragma once
// The RGB-D camera: pinhole intrinsics plus ORB-SLAM2's virtual stereo
// baseline (bf = baseline x fx), which turns a depth into a right-image
// coordinate u_r = u - bf / z so depth constrains the pose like stereo.
#include <Eigen/Core>

namespace depot::slam {

struct PinholeCamera {
  int width = 640;
  int height = 480;
  double fx = 535.4, fy = 539.2, cx = 320.1, cy = 247.6;
  double bf = 40.0;              // baseline (m) x fx: 0.075 m for a Kinect
  double depth_factor = 5000.0;  // depth PNG units per metre
  double close_depth = 3.0;      // m: points closer are "close" (reliable depth)

  Eigen::Vector2d project(const Eigen::Vector3d& p_cam) const {
    return {fx * p_cam.x() / p_cam.z() + cx, fy * p_cam.y() / p_cam.z() + cy};
  }
  Eigen::Vector3d unproject(double u, double v, double z) const {
    return {(u - cx) * z / fx, (v - cy) * z / fy, z};
  }
  bool in_image(double u, double v) const { return u >= 0 && v >= 0 && u < width && v < height; }
  double right_u(double u, double z) const { return u - bf / z; }
};

}  // namespace depot::slam
