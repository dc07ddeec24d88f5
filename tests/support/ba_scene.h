#pragma once
// Synthetic maps for optimisation tests: keyframes along a short path seeing
// a few hundred points with known truth, keypoints with pixel noise and
// depth, poses and points perturbed (slam/optimize, slam/loop tests).
#include <cmath>
#include <cstdint>
#include <vector>

#include "common/rng.h"
#include "slam/data/map.h"

namespace depot::slam::test {

constexpr double kDeg = M_PI / 180.0;

const ScaleLevels& levels();
// A rotation of `angle` rad about a random axis.
Eigen::Matrix3d random_rotation(Rng& rng, double angle);
Eigen::Vector3d random_direction(Rng& rng);
// T_cw perturbed by exactly `trans` m of camera-centre motion and `angle` rad.
Pose perturb(const Pose& T_cw, Rng& rng, double trans, double angle);
// A camera looking roughly along +z from `center`, yawed by `yaw` rad.
Pose camera_pose(const Eigen::Vector3d& center, double yaw);

struct Keypoint {
  double u, v, z;  // z <= 0: no depth
  int octave;
};

// Features filled directly from synthetic keypoints (depth -> u_right).
Features make_features(const std::vector<Keypoint>& kps, const PinholeCamera& cam);

struct BaScene {
  Map map;
  std::vector<KeyFrame*> kfs;
  std::vector<Pose> truth;
  // Per keyframe, the keypoint indices whose keypoint was made a gross outlier.
  std::vector<std::vector<size_t>> gross;
};

// 5 keyframes along a short sideways path observing 400 points; keyframe 0
// exact, the others perturbed by 2 cm / 1 deg, the points by 3 cm.
void build_ba_scene(BaScene& s, uint64_t seed, int n_gross_per_kf = 0);

}  // namespace depot::slam::test
