#pragma once
// Camera trajectories: smooth functions of time giving the camera pose
// T_world_camera (OpenCV camera axes: x right, y down, z forward).
#include <memory>
#include <vector>

#include "common/pose.h"
#include "common/tum_io.h"
#include "sim/scenario/path.h"
#include "sim/scenario/scenario.h"

namespace depot::sim {

// Rotation whose z axis looks from `from` to `to`, with x level (no roll).
Eigen::Matrix3d look_at_rotation(const Eigen::Vector3d& from, const Eigen::Vector3d& to);

// Smooth, seeded hand tremor: a few sinusoids per axis (about 1-2 mm and
// 0.2 deg at scale 1), like a person holding a Kinect.
class HandTremor {
 public:
  HandTremor(uint64_t seed, double scale);
  Pose at(double t) const;  // a small pose offset in the camera frame

 private:
  struct Wave {
    double amplitude, frequency, phase;
  };
  std::vector<Wave> waves_[6];
};

class CameraMotion {
 public:
  // `start_time`: the absolute timestamp of the first frame.
  CameraMotion(const CameraMotionSpec& spec, uint64_t seed, double start_time);
  // Pose in the simulator's world at absolute timestamp t.
  Pose pose_at(double t) const;
  // Maps dataset coordinates into the simulator's world. Identity except when
  // replaying a trajectory file, whose own frame becomes the dataset frame so
  // groundtruth.txt reproduces the file.
  const Pose& world_from_dataset() const { return world_from_dataset_; }

 private:
  Pose pose_relative(double dt) const;

  CameraMotionSpec spec_;
  double start_time_;
  HandTremor tremor_;
  Eigen::Matrix3d base_rotation_;
  Path2D path_;
  std::vector<StampedPose> file_poses_;
  Pose world_from_dataset_ = Pose::Identity();
};

}  // namespace depot::sim
