// The solvers on correspondences with a known answer: points seen by a
// camera at a known pose, a share of them replaced by wrong matches.
#include <random>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "slam/solve/pnp_ransac.h"
#include "slam/solve/rigid_ransac.h"

namespace depot::slam {
namespace {

Pose known_pose() {
  Pose T = Pose::Identity();
  T.rotate(Eigen::AngleAxisd(0.3, Eigen::Vector3d(0.2, 1.0, -0.1).normalized()));
  T.pretranslate(Eigen::Vector3d(0.4, -0.1, 0.25));
  return T;
}

// Points 1-5 m in front of a camera at the identity, spread over its view.
std::vector<Eigen::Vector3d> points_in_view(const PinholeCamera& camera, int n, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(20, camera.width - 20), v(20, camera.height - 20),
      z(1.0, 5.0);
  std::vector<Eigen::Vector3d> out;
  for (int i = 0; i < n; ++i) out.push_back(camera.unproject(u(rng), v(rng), z(rng)));
  return out;
}

double rotation_error_rad(const Pose& a, const Pose& b) {
  return Eigen::AngleAxisd(a.linear() * b.linear().transpose()).angle();
}

TEST(PnpRansac, FindsThePoseAndItsInliersAmongWrongMatches) {
  const PinholeCamera camera;
  const Pose T_cw = known_pose();
  // Points seen by the camera at T_cw, written in the world.
  std::vector<Eigen::Vector3d> world;
  std::vector<Eigen::Vector2d> pixels;
  const Pose T_wc = T_cw.inverse();
  for (const Eigen::Vector3d& p : points_in_view(camera, 120, 3)) {
    world.push_back(T_wc * p);
    pixels.push_back(camera.project(p));
  }
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0, camera.width), v(0, camera.height);
  for (size_t i = 0; i < pixels.size(); i += 3) pixels[i] = {u(rng), v(rng)};  // a third wrong
  const PnpResult r = solve_pnp_ransac(world, pixels, camera);
  ASSERT_TRUE(r.ok);
  EXPECT_LT(rotation_error_rad(r.T_cw, T_cw), 1e-4);
  EXPECT_LT((r.T_cw.translation() - T_cw.translation()).norm(), 1e-3);
  for (int i : r.inliers) EXPECT_NE(i % 3, 0) << "wrong match " << i << " kept";
  EXPECT_GE(r.inliers.size(), 78u);  // of the 80 right ones
}

TEST(PnpRansac, RefusesTooFewCorrespondencesOrInliers) {
  const PinholeCamera camera;
  std::vector<Eigen::Vector3d> world = points_in_view(camera, 5, 1);
  std::vector<Eigen::Vector2d> pixels;
  for (const Eigen::Vector3d& p : world) pixels.push_back(camera.project(p));
  EXPECT_FALSE(solve_pnp_ransac(world, pixels, camera).ok) << "five pairs";
  world = points_in_view(camera, 30, 2);
  pixels.clear();
  for (const Eigen::Vector3d& p : world) pixels.push_back(camera.project(p));
  EXPECT_TRUE(solve_pnp_ransac(world, pixels, camera, 300, 4.0, 30).ok);
  EXPECT_FALSE(solve_pnp_ransac(world, pixels, camera, 300, 4.0, 31).ok) << "min_inliers 31";
}

// Pairs of a point seen in camera A and in frame B (B's camera at B's
// origin), related by T_ab; every fourth pair a wrong match.
std::vector<RigidCorrespondence> rigid_pairs(const PinholeCamera& camera, const Pose& T_ab) {
  std::vector<RigidCorrespondence> pairs;
  const Pose T_ba = T_ab.inverse();
  const std::vector<Eigen::Vector3d> in_a = points_in_view(camera, 100, 7);
  for (const Eigen::Vector3d& p : in_a) {
    RigidCorrespondence c;
    c.in_a = p;
    c.in_b = T_ba * p;
    if (c.in_b.z() <= 0.5) continue;  // behind camera B
    c.pixel_a = camera.project(c.in_a);
    c.pixel_b = camera.project(c.in_b);
    pairs.push_back(c);
  }
  const std::vector<Eigen::Vector3d> wrong = points_in_view(camera, 100, 8);
  for (size_t i = 0; i < pairs.size(); i += 4) {
    pairs[i].in_a = wrong[i];
    pairs[i].pixel_a = camera.project(wrong[i]);
  }
  return pairs;
}

TEST(RigidRansac, FindsTheTransformAndLeavesTheWrongMatchesOut) {
  const PinholeCamera camera;
  Pose T_ab = Pose::Identity();
  T_ab.rotate(Eigen::AngleAxisd(0.15, Eigen::Vector3d::UnitY()));
  T_ab.pretranslate(Eigen::Vector3d(0.3, 0.0, -0.2));
  const std::vector<RigidCorrespondence> pairs = rigid_pairs(camera, T_ab);
  ASSERT_GT(pairs.size(), 60u);
  const RigidResult r = solve_rigid_ransac(pairs, camera);
  ASSERT_TRUE(r.ok);
  EXPECT_LT(rotation_error_rad(r.T_ab, T_ab), 1e-6);
  EXPECT_LT((r.T_ab.translation() - T_ab.translation()).norm(), 1e-6);
  size_t right = 0;
  for (size_t i = 0; i < pairs.size(); ++i) right += i % 4 != 0;
  EXPECT_EQ(r.inliers.size(), right);
  for (int i : r.inliers) EXPECT_NE(i % 4, 0) << "wrong match " << i << " kept";
  // The same pairs and seed give the same answer.
  const RigidResult again = solve_rigid_ransac(pairs, camera);
  EXPECT_EQ(again.inliers, r.inliers);
  EXPECT_TRUE(again.T_ab.isApprox(r.T_ab, 0.0));
}

TEST(RigidRansac, RefusesFewerPairsThanItsInlierBar) {
  const PinholeCamera camera;
  std::vector<RigidCorrespondence> pairs = rigid_pairs(camera, Pose::Identity());
  pairs.resize(19);
  EXPECT_FALSE(solve_rigid_ransac(pairs, camera).ok) << "19 pairs, 20 inliers needed";
  EXPECT_TRUE(solve_rigid_ransac(pairs, camera, 300, 10).ok);
}

}  // namespace
}  // namespace depot::slam
