#pragma once
// Helpers shared by the eval tests: synthetic trajectories, rigid motions and
// scratch files.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "common/pose.h"
#include "common/tum_io.h"

namespace depot::eval::testing {

inline Pose rotation_about(const Eigen::Vector3d& axis, double angle_rad,
                           const Eigen::Vector3d& translation = Eigen::Vector3d::Zero()) {
  return make_pose(Eigen::AngleAxisd(angle_rad, axis.normalized()).toRotationMatrix(), translation);
}

inline double deg(double d) {
  return d * M_PI / 180.0;
}

// A hand-held-like motion: a slow helix with the camera turning about a
// tilted axis, sampled at `rate_hz` from t0.
inline std::vector<StampedPose> helix_trajectory(size_t n, double rate_hz, double t0 = 100.0) {
  std::vector<StampedPose> out;
  for (size_t k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) / rate_hz;
    const Eigen::Vector3d p(1.5 * std::cos(0.4 * t), 1.0 * std::sin(0.4 * t), 0.3 + 0.05 * t);
    const Pose orientation = rotation_about({0.2, 0.3, 1.0}, 0.35 * t);
    out.push_back({t0 + t, make_pose(Eigen::Matrix3d(orientation.linear()), p)});
  }
  return out;
}

// The same poses seen from another world frame: T * pose for every pose.
inline std::vector<StampedPose> moved(const std::vector<StampedPose>& poses, const Pose& t) {
  std::vector<StampedPose> out = poses;
  for (StampedPose& p : out) p.pose = t * p.pose;
  return out;
}

inline std::string scratch_path(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(DEPOT_BINARY_DIR) / "eval_test_scratch";
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

inline std::string write_scratch_file(const std::string& name, const std::string& text) {
  const std::string path = scratch_path(name);
  std::ofstream(path) << text;
  return path;
}

inline std::string read_whole_file(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace depot::eval::testing
