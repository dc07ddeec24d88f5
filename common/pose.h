#pragma once
// Rigid poses. Convention everywhere: T_a_b maps points of frame b into frame a;
// a camera pose is camera-to-world (T_world_camera), as in TUM files.
#include <Eigen/Geometry>

namespace depot {

using Pose = Eigen::Isometry3d;

inline Pose make_pose(const Eigen::Quaterniond& q, const Eigen::Vector3d& t) {
  Pose p = Pose::Identity();
  p.linear() = q.normalized().toRotationMatrix();
  p.translation() = t;
  return p;
}

inline Pose make_pose(const Eigen::Matrix3d& r, const Eigen::Vector3d& t) {
  Pose p = Pose::Identity();
  p.linear() = r;
  p.translation() = t;
  return p;
}

// Rotation angle (rad) of the relative rotation between two poses.
inline double rotation_angle_between(const Pose& a, const Pose& b) {
  Eigen::AngleAxisd aa(a.linear().transpose() * b.linear());
  return std::abs(aa.angle());
}

inline double translation_between(const Pose& a, const Pose& b) {
  return (a.translation() - b.translation()).norm();
}

// Interpolates between two poses (slerp on rotation, linear on translation).
inline Pose interpolate(const Pose& a, const Pose& b, double s) {
  Eigen::Quaterniond qa(a.linear()), qb(b.linear());
  Eigen::Vector3d t = (1.0 - s) * a.translation() + s * b.translation();
  return make_pose(qa.slerp(s, qb), t);
}

}  // namespace depot
