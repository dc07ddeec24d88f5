#pragma once
// Small kinematic helpers shared by the actor rigs (local frame: x forward,
// y left, z up).
#include <cmath>

#include "common/pose.h"

namespace depot::sim {

inline Eigen::Matrix3d rot_x(double a) {
  return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitX()).matrix();
}
inline Eigen::Matrix3d rot_y(double a) {
  return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitY()).matrix();
}
inline Eigen::Matrix3d rot_z(double a) {
  return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).matrix();
}
inline double deg(double d) {
  return d * M_PI / 180.0;
}

// A limb of `length` hanging from `joint`, swung forward by `pitch` (rad,
// 0 = straight down) within the plane given by the parent rotation. Returns
// the pose of a capsule centred on the limb (its z axis along the limb) and
// writes the far end to `end`.
inline Pose limb(const Eigen::Vector3d& joint, const Eigen::Matrix3d& parent, double pitch,
                 double length, Eigen::Vector3d* end = nullptr) {
  Eigen::Vector3d dir = parent * Eigen::Vector3d(std::sin(pitch), 0.0, -std::cos(pitch));
  if (end) *end = joint + dir * length;
  return make_pose(Eigen::Matrix3d(parent * rot_y(-pitch)), joint + dir * (0.5 * length));
}

}  // namespace depot::sim
