#include "tests/support/real_frame.h"

#include <cmath>
#include <filesystem>

#include <Eigen/Geometry>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "common/error.h"

namespace depot::test {

std::string real_frame_folder() {
  return std::string(DEPOT_SHARED_DATA) + "/tum/fr3_walking_xyz_frame";
}

RealFrame load_real_frame() {
  namespace fs = std::filesystem;
  const std::string folder = real_frame_folder();
  if (!fs::is_directory(folder)) fail(folder, "shared data missing");
  RealFrame f;
  for (const auto& e : fs::directory_iterator(folder + "/rgb"))
    f.bgr = cv::imread(e.path().string(), cv::IMREAD_COLOR);
  for (const auto& e : fs::directory_iterator(folder + "/depth")) {
    const cv::Mat raw = cv::imread(e.path().string(), cv::IMREAD_UNCHANGED);
    raw.convertTo(f.depth, CV_32F, 1.0 / 5000.0);
  }
  if (f.bgr.empty() || f.depth.empty()) fail(folder, "no rgb or depth image");
  return f;
}

Eigen::Matrix3d turn(double yaw_deg, double pitch_deg) {
  const double d = M_PI / 180.0;
  return (Eigen::AngleAxisd(yaw_deg * d, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(pitch_deg * d, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

Pose turned_pose(const Eigen::Matrix3d& rotation) {
  Pose T_cw = Pose::Identity();
  T_cw.linear() = rotation.transpose();
  return T_cw;
}

RealFrame turned_view(const RealFrame& frame, const slam::PinholeCamera& camera,
                      const Eigen::Matrix3d& rotation) {
  // Pixel p' of the turned camera sees direction d = R K^-1 p' of the
  // original camera: colour and depth come from K d / d.z, and a depth z
  // there is z / d.z along the turned camera's axis.
  const int w = frame.bgr.cols, h = frame.bgr.rows;
  cv::Mat map_x(h, w, CV_32F), map_y(h, w, CV_32F), scale(h, w, CV_32F);
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const Eigen::Vector3d d = rotation * camera.unproject(u, v, 1.0);
      const bool ahead = d.z() > 1e-6;
      const Eigen::Vector2d src = ahead ? camera.project(d) : Eigen::Vector2d(-1, -1);
      map_x.at<float>(v, u) = static_cast<float>(src.x());
      map_y.at<float>(v, u) = static_cast<float>(src.y());
      scale.at<float>(v, u) = ahead ? static_cast<float>(1.0 / d.z()) : 0.0f;
    }
  RealFrame out;
  cv::remap(frame.bgr, out.bgr, map_x, map_y, cv::INTER_LINEAR, cv::BORDER_CONSTANT,
            cv::Scalar::all(0));
  cv::remap(frame.depth, out.depth, map_x, map_y, cv::INTER_NEAREST, cv::BORDER_CONSTANT,
            cv::Scalar(0));
  out.depth = out.depth.mul(scale);
  return out;
}

double rotation_error_deg(const Pose& a, const Pose& b) {
  const Eigen::AngleAxisd e(a.linear() * b.linear().transpose());
  return std::abs(e.angle()) * 180.0 / M_PI;
}

}  // namespace depot::test
