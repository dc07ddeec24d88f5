#include "sim/camera/camera_motion.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "common/rng.h"
#include "sim/actors/limb.h"

namespace depot::sim {

Eigen::Matrix3d look_at_rotation(const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  Eigen::Vector3d z = (to - from).normalized();
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  if (std::abs(z.dot(up)) > 0.999) up = Eigen::Vector3d::UnitY();
  Eigen::Vector3d x = z.cross(up).normalized();
  Eigen::Vector3d y = z.cross(x);
  Eigen::Matrix3d r;
  r.col(0) = x;
  r.col(1) = y;
  r.col(2) = z;
  return r;
}

HandTremor::HandTremor(uint64_t seed, double scale) {
  Rng rng(derive_seed(seed, 0x7e3));
  for (int axis = 0; axis < 6; ++axis) {
    const double base = axis < 3 ? 0.0012 : deg(0.18);
    for (int k = 0; k < 3; ++k) {
      waves_[axis].push_back({scale * base * rng.uniform(0.4, 1.0) / (k + 1),
                              rng.uniform(0.3, 2.5) * (k + 1), rng.uniform(0.0, 2.0 * M_PI)});
    }
  }
}

Pose HandTremor::at(double t) const {
  double v[6];
  for (int axis = 0; axis < 6; ++axis) {
    v[axis] = 0.0;
    for (const auto& w : waves_[axis])
      v[axis] += w.amplitude * std::sin(2.0 * M_PI * w.frequency * t + w.phase);
  }
  Eigen::Matrix3d r = rot_x(v[3]) * rot_y(v[4]) * rot_z(v[5]);
  return make_pose(r, Eigen::Vector3d(v[0], v[1], v[2]));
}

CameraMotion::CameraMotion(const CameraMotionSpec& spec, uint64_t seed, double start_time)
    : spec_(spec), start_time_(start_time), tremor_(seed, spec.tremor) {
  base_rotation_ = spec.type == "waypoints" ? Eigen::Matrix3d::Identity()
                                            : look_at_rotation(spec.position, spec.look_at);
  if (spec.type == "waypoints") path_ = Path2D(spec.path, spec.loop, 0.8);
  if (spec.type == "file") {
    file_poses_ = read_tum_trajectory(spec.file);
    if (spec.anchor_first_pose) {
      // Place the file's first pose at position/look_at in the depot.
      Pose desired = make_pose(base_rotation_, spec.position);
      world_from_dataset_ = desired * file_poses_.front().pose.inverse();
    }
  }
}

Pose CameraMotion::pose_at(double t) const {
  if (spec_.type == "file") {
    // Interpolate the file's poses at t (clamped to its time span).
    const auto& fp = file_poses_;
    Pose p;
    if (t <= fp.front().timestamp) {
      p = fp.front().pose;
    } else if (t >= fp.back().timestamp) {
      p = fp.back().pose;
    } else {
      auto it = std::lower_bound(fp.begin(), fp.end(), t,
                                 [](const StampedPose& a, double v) { return a.timestamp < v; });
      if (it->timestamp == t) {
        p = it->pose;
      } else {
        const StampedPose& b = *it;
        const StampedPose& a = *(it - 1);
        p = interpolate(a.pose, b.pose, (t - a.timestamp) / (b.timestamp - a.timestamp));
      }
    }
    return world_from_dataset_ * p;
  }
  return pose_relative(t - start_time_) * tremor_.at(t - start_time_);
}

Pose CameraMotion::pose_relative(double dt) const {
  const double w = 2.0 * M_PI;
  const Eigen::Vector3d& c = spec_.position;
  if (spec_.type == "xyz") {
    // Hand-held translation along the camera's three axes, about +-A.
    const double a = spec_.amplitude > 0 ? spec_.amplitude : 0.3;
    const double period = spec_.period > 0 ? spec_.period : 7.0;
    Eigen::Vector3d offset(a * std::sin(w * dt / period),
                           0.7 * a * std::sin(w * dt / (1.23 * period) + 1.3),
                           0.6 * a * std::sin(w * dt / (1.41 * period) + 2.1));
    return make_pose(base_rotation_, c + base_rotation_ * offset);
  }
  if (spec_.type == "rpy") {
    // Rotation in place about the camera's axes: yaw, pitch and roll.
    const double a = deg(spec_.amplitude > 0 ? spec_.amplitude : 25.0);
    const double period = spec_.period > 0 ? spec_.period : 8.0;
    Eigen::Matrix3d r = base_rotation_ * rot_y(a * std::sin(w * dt / period)) *
                        rot_x(0.8 * a * std::sin(w * dt / (1.31 * period) + 0.7)) *
                        rot_z(0.8 * a * std::sin(w * dt / (1.57 * period) + 1.9));
    return make_pose(r, c);
  }
  if (spec_.type == "halfsphere") {
    // On a half sphere around `position` (radius A), on the side away from the
    // scene, always looking at look_at (inwards, through the centre).
    const double radius = spec_.amplitude > 0 ? spec_.amplitude : 0.5;
    const double period = spec_.period > 0 ? spec_.period : 12.0;
    const double azimuth = deg(70.0) * std::sin(w * dt / period);
    const double elevation = deg(35.0) + deg(30.0) * std::sin(w * dt / (1.37 * period) - 1.2);
    Eigen::Vector3d forward = spec_.look_at - c;
    forward.z() = 0.0;
    forward.normalize();
    Eigen::Vector3d left = Eigen::Vector3d::UnitZ().cross(forward);
    Eigen::Vector3d pos = c + radius * (-std::cos(elevation) * std::cos(azimuth) * forward +
                                        std::cos(elevation) * std::sin(azimuth) * left +
                                        std::sin(elevation) * Eigen::Vector3d::UnitZ());
    return make_pose(look_at_rotation(pos, spec_.look_at), pos);
  }
  if (spec_.type == "waypoints") {
    // A robot-mounted camera: accelerates gently, follows the path at speed,
    // looking along its heading, slightly tilted down.
    const double ramp = 2.0;  // s to reach full speed
    const double s =
        dt < ramp ? spec_.speed * dt * dt / (2.0 * ramp) : spec_.speed * (dt - 0.5 * ramp);
    Eigen::Vector2d xy = path_.position(s);
    double heading = path_.heading(s);
    Eigen::Vector3d pos(xy.x(), xy.y(), spec_.height);
    Eigen::Vector3d dir(std::cos(heading), std::sin(heading), -std::tan(deg(spec_.pitch_deg)));
    return make_pose(look_at_rotation(pos, pos + dir), pos);
  }
  // static: the base pose; tremor is added by the caller.
  return make_pose(base_rotation_, c);
}

}  // namespace depot::sim
