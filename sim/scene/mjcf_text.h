#pragma once
// Numbers, vectors and rotations as MJCF attribute text, shared by the scene
// builder and the mesh props.
#include <fmt/format.h>

#include <cmath>
#include <string>

#include <Eigen/Geometry>

namespace depot::sim {

// Six significant digits; |v| < 1e-12 is written 0 (no "-0" or 1e-17 noise).
inline std::string num(double v) {
  return fmt::format("{:.6g}", std::abs(v) < 1e-12 ? 0.0 : v);
}

inline std::string vec(const Eigen::Vector3d& v) {
  return num(v.x()) + " " + num(v.y()) + " " + num(v.z());
}

// A rotation as MJCF's quat="w x y z".
inline std::string quat(const Eigen::Matrix3d& r) {
  Eigen::Quaterniond q(r);
  q.normalize();
  return num(q.w()) + " " + num(q.x()) + " " + num(q.y()) + " " + num(q.z());
}

}  // namespace depot::sim
