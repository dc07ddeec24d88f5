#include "slam/solve/rigid_ransac.h"

#include <algorithm>
#include <random>

#include <Eigen/Geometry>

namespace depot::slam {
namespace {

Pose fit(const std::vector<RigidCorrespondence>& pairs, const std::vector<int>& which) {
  Eigen::Matrix3Xd a(3, which.size()), b(3, which.size());
  for (size_t k = 0; k < which.size(); ++k) {
    a.col(static_cast<Eigen::Index>(k)) = pairs[which[k]].in_a;
    b.col(static_cast<Eigen::Index>(k)) = pairs[which[k]].in_b;
  }
  Pose T;
  T.matrix() = Eigen::umeyama(b, a, false);
  return T;
}

bool reprojects(const Eigen::Vector3d& p_cam, const Eigen::Vector2d& pixel,
                const PinholeCamera& camera, double max_px) {
  if (p_cam.z() <= 0) return false;
  return (camera.project(p_cam) - pixel).squaredNorm() <= max_px * max_px;
}

std::vector<int> inliers_of(const std::vector<RigidCorrespondence>& pairs, const Pose& T_ab,
                            const PinholeCamera& camera) {
  const Pose T_ba = T_ab.inverse();
  std::vector<int> out;
  for (size_t i = 0; i < pairs.size(); ++i) {
    const RigidCorrespondence& c = pairs[i];
    if (reprojects(T_ab * c.in_b, c.pixel_a, camera, c.max_error_px) &&
        reprojects(c.T_b_camera * (T_ba * c.in_a), c.pixel_b, camera, c.max_error_px))
      out.push_back(static_cast<int>(i));
  }
  return out;
}

}  // namespace

RigidResult solve_rigid_ransac(const std::vector<RigidCorrespondence>& pairs,
                               const PinholeCamera& camera, int iterations, int min_inliers,
                               uint64_t seed) {
  RigidResult best;
  if (static_cast<int>(pairs.size()) < std::max(3, min_inliers)) return best;
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<size_t> pick(0, pairs.size() - 1);
  for (int it = 0; it < iterations; ++it) {
    std::vector<int> sample;
    while (sample.size() < 3) {
      const int k = static_cast<int>(pick(rng));
      if (std::find(sample.begin(), sample.end(), k) == sample.end()) sample.push_back(k);
    }
    const Pose T = fit(pairs, sample);
    std::vector<int> in = inliers_of(pairs, T, camera);
    if (in.size() > best.inliers.size()) {
      best.T_ab = T;
      best.inliers = std::move(in);
    }
  }
  if (static_cast<int>(best.inliers.size()) < min_inliers) return RigidResult{};
  // Refit on all inliers, keep it when it holds at least as many.
  const Pose refined = fit(pairs, best.inliers);
  std::vector<int> in = inliers_of(pairs, refined, camera);
  if (in.size() >= best.inliers.size()) best.T_ab = refined, best.inliers = std::move(in);
  best.ok = true;
  return best;
}

}  // namespace depot::slam
