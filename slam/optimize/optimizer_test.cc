#include "slam/optimize/optimizer.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "common/rng.h"
#include "slam/data/map_point.h"
#include "tests/support/ba_scene.h"

namespace depot::slam {
namespace {

using namespace depot::slam::test;

// ---------------------------------------------------------------------------
// Pose-only optimisation.

struct PoseScene {
  Map map;  // owns the map points
  Frame frame;
  Pose truth;
  std::vector<bool> gross;  // per keypoint
};

void build_pose_scene(PoseScene& s, uint64_t seed, bool with_depth, int n = 300,
                      double outlier_ratio = 0.2) {
  Rng rng(seed);
  const PinholeCamera cam;
  s.truth = camera_pose(Eigen::Vector3d(0.3, -0.2, 0.5), 0.2);
  const Pose T_wc = s.truth.inverse();
  std::vector<Keypoint> kps;
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < n; ++i) {
    const double u = rng.uniform(10, cam.width - 10), v = rng.uniform(10, cam.height - 10);
    const double z = rng.uniform(0.8, 6.0);
    points.push_back(T_wc * cam.unproject(u, v, z));
    const int octave = static_cast<int>(rng.below(4));
    const bool gross = rng.uniform() < outlier_ratio;
    s.gross.push_back(gross);
    Keypoint k{};
    k.octave = octave;
    if (gross) {  // a wrong match: somewhere else in the image, with that place's depth
      k.u = rng.uniform(0, cam.width);
      k.v = rng.uniform(0, cam.height);
      k.z = rng.uniform(0.8, 6.0);
    } else {
      k.u = u + rng.normal(0, 0.5);
      k.v = v + rng.normal(0, 0.5);
      k.z = z * (1.0 + rng.normal(0, 0.002));
    }
    if (!with_depth) k.z = -1;
    kps.push_back(k);
  }
  s.frame = Frame(1, 0.0, make_features(kps, cam));
  for (int i = 0; i < n; ++i) s.frame.map_points[i] = s.map.create_map_point(points[i], nullptr);
  s.frame.T_cw = perturb(s.truth, rng, 0.10, 5 * kDeg);
}

struct OutlierStats {
  double gross_flagged = 0, inlier_flagged = 0;
};

OutlierStats outlier_stats(const PoseScene& s) {
  int n_gross = 0, gross_flagged = 0, n_in = 0, in_flagged = 0;
  for (size_t i = 0; i < s.gross.size(); ++i) {
    if (s.gross[i]) {
      ++n_gross;
      gross_flagged += s.frame.outlier[i];
    } else {
      ++n_in;
      in_flagged += s.frame.outlier[i];
    }
  }
  return {static_cast<double>(gross_flagged) / n_gross, static_cast<double>(in_flagged) / n_in};
}

void expect_pose_recovered(PoseScene& s, const char* what) {
  const Pose start = s.frame.T_cw;
  const int inliers = optimize_pose(s.frame);
  const double t_err = translation_between(s.frame.T_cw.inverse(), s.truth.inverse());
  const double r_err = rotation_angle_between(s.frame.T_cw, s.truth) / kDeg;
  const OutlierStats o = outlier_stats(s);
  std::printf(
      "[%s] start %.3f m / %.2f deg -> %.4f m / %.4f deg, inliers %d, gross flagged %.1f %%, "
      "inliers flagged %.1f %%\n",
      what, translation_between(start.inverse(), s.truth.inverse()),
      rotation_angle_between(start, s.truth) / kDeg, t_err, r_err, inliers, 100 * o.gross_flagged,
      100 * o.inlier_flagged);
  EXPECT_LT(t_err, 0.01);
  EXPECT_LT(r_err, 0.2);
  EXPECT_GE(o.gross_flagged, 0.9);
  EXPECT_LT(o.inlier_flagged, 0.05);
  int flagged = 0;
  for (bool b : s.frame.outlier) flagged += b;
  EXPECT_EQ(inliers, static_cast<int>(s.frame.size()) - flagged);
}

TEST(OptimizePose, RgbdRecoversPoseAndFlagsOutliers) {
  for (uint64_t seed : {1u, 2u, 3u}) {
    PoseScene s;
    build_pose_scene(s, seed, true);
    expect_pose_recovered(s, "rgbd");
  }
}

TEST(OptimizePose, MonocularRecoversPoseAndFlagsOutliers) {
  for (uint64_t seed : {4u, 5u, 6u}) {
    PoseScene s;
    build_pose_scene(s, seed, false);
    expect_pose_recovered(s, "mono");
  }
}

TEST(OptimizePose, IgnoresUnmatchedAndBadPoints) {
  PoseScene s;
  build_pose_scene(s, 7, true, 300, 0.0);
  // Half the keypoints unmatched, a few matched to bad points (with wrong positions).
  for (size_t i = 0; i < s.frame.size(); i += 2) s.frame.map_points[i] = nullptr;
  for (size_t i = 1; i < 40; i += 2) {
    s.frame.map_points[i]->bad = true;
    s.frame.map_points[i]->position += Eigen::Vector3d(1, 1, 1);
  }
  const int inliers = optimize_pose(s.frame);
  EXPECT_GE(inliers, 120);
  EXPECT_LE(inliers, 130);
  EXPECT_LT(translation_between(s.frame.T_cw.inverse(), s.truth.inverse()), 0.01);
}

TEST(OptimizePose, TooFewCorrespondencesLeavesPose) {
  PoseScene s;
  build_pose_scene(s, 8, true);
  for (size_t i = 2; i < s.frame.size(); ++i) s.frame.map_points[i] = nullptr;
  const Pose before = s.frame.T_cw;
  EXPECT_EQ(optimize_pose(s.frame), 0);
  EXPECT_TRUE(s.frame.T_cw.isApprox(before, 0.0));
}

// ---------------------------------------------------------------------------
// Local bundle adjustment.

TEST(LocalBundleAdjustment, ReducesReprojectionError) {
  BaScene s;
  build_ba_scene(s, 11);
  ASSERT_EQ(s.kfs.back()->covisibles().size(), 4u);
  const Pose kf0_before = s.kfs[0]->T_cw;
  const double before = reprojection_rmse(s.map);

  const auto t0 = std::chrono::steady_clock::now();
  local_bundle_adjustment(s.kfs.back(), s.map, nullptr);
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();

  const double after = reprojection_rmse(s.map);
  double max_t = 0, max_r = 0;
  for (size_t k = 1; k < s.kfs.size(); ++k) {
    max_t = std::max(max_t, translation_between(s.kfs[k]->T_cw.inverse(), s.truth[k].inverse()));
    max_r = std::max(max_r, rotation_angle_between(s.kfs[k]->T_cw, s.truth[k]) / kDeg);
  }
  size_t links = 0;
  for (const MapPoint* mp : s.map.map_points()) links += mp->observations.size();
  std::printf(
      "[local BA] rmse %.3f -> %.3f px, pose error max %.4f m / %.4f deg, %zu links, "
      "%.2f ms\n",
      before, after, max_t, max_r, links, ms);
  RecordProperty("local_ba_ms", std::to_string(ms));
  EXPECT_GT(before / after, 5.0);
  EXPECT_LT(after, 1.0);
  EXPECT_TRUE(s.kfs[0]->T_cw.isApprox(kf0_before, 0.0));  // bit-identical
  EXPECT_LT(max_t, 0.01);
  EXPECT_LT(max_r, 0.2);
  // Plain noise: (almost) nothing is unlinked.
  size_t observed = 0;
  for (const KeyFrame* kf : s.kfs) observed += kf->tracked_map_points(0);
  EXPECT_EQ(observed, links);
  EXPECT_GT(links, 1900u);
}

TEST(LocalBundleAdjustment, UnlinksGrossOutliers) {
  BaScene s;
  build_ba_scene(s, 12, 8);
  local_bundle_adjustment(s.kfs.back(), s.map, nullptr);
  int erased = 0, total = 0;
  for (size_t k = 0; k < s.kfs.size(); ++k)
    for (size_t idx : s.gross[k]) {
      ++total;
      erased += s.kfs[k]->map_points[idx] == nullptr;
    }
  // Every erased link is gone on both sides.
  for (const KeyFrame* kf : s.kfs)
    for (size_t i = 0; i < kf->map_points.size(); ++i) {
      const MapPoint* mp = kf->map_points[i];
      if (!mp) continue;
      auto it = mp->observations.find(const_cast<KeyFrame*>(kf));
      ASSERT_TRUE(it != mp->observations.end());
      EXPECT_EQ(it->second, i);
    }
  std::printf("[local BA] gross outliers unlinked: %d / %d, rmse after %.3f px\n", erased, total,
              reprojection_rmse(s.map));
  EXPECT_GE(erased, total * 9 / 10);
  EXPECT_LT(reprojection_rmse(s.map), 1.0);
}

TEST(LocalBundleAdjustment, AbortBeforeCallChangesNothing) {
  BaScene s;
  build_ba_scene(s, 13, 8);
  std::vector<Pose> poses;
  for (const KeyFrame* kf : s.kfs) poses.push_back(kf->T_cw);
  std::vector<Eigen::Vector3d> positions;
  std::vector<size_t> n_obs;
  for (const MapPoint* mp : s.map.map_points()) {
    positions.push_back(mp->position);
    n_obs.push_back(mp->observations.size());
  }
  std::atomic<bool> abort{true};
  local_bundle_adjustment(s.kfs.back(), s.map, &abort);
  for (size_t k = 0; k < s.kfs.size(); ++k) EXPECT_TRUE(s.kfs[k]->T_cw.isApprox(poses[k], 0.0));
  size_t i = 0;
  for (const MapPoint* mp : s.map.map_points()) {
    EXPECT_EQ(mp->position, positions[i]);
    EXPECT_EQ(mp->observations.size(), n_obs[i]);
    ++i;
  }
  // The map mutex is free again.
  EXPECT_TRUE(s.map.mutex().try_lock());
  s.map.mutex().unlock();
}

TEST(LocalBundleAdjustment, SkipsBadKeyframe) {
  BaScene s;
  build_ba_scene(s, 14);
  s.kfs.back()->bad = true;
  const Pose before = s.kfs[2]->T_cw;
  local_bundle_adjustment(s.kfs.back(), s.map, nullptr);
  EXPECT_TRUE(s.kfs[2]->T_cw.isApprox(before, 0.0));
}

// ---------------------------------------------------------------------------
// Global bundle adjustment.

TEST(GlobalBundleAdjustment, RecoversEveryKeyframeAndReturnsWithoutWriting) {
  BaScene s;
  build_ba_scene(s, 21);
  std::vector<Pose> poses;
  for (const KeyFrame* kf : s.kfs) poses.push_back(kf->T_cw);
  const double before = reprojection_rmse(s.map);
  const GlobalBaResult result = global_bundle_adjustment(s.map, nullptr, 10);
  ASSERT_TRUE(result.completed);
  ASSERT_EQ(result.keyframes.size(), s.kfs.size());
  EXPECT_EQ(result.points.size(), s.map.n_map_points());
  // Nothing written yet.
  for (size_t k = 0; k < s.kfs.size(); ++k) EXPECT_TRUE(s.kfs[k]->T_cw.isApprox(poses[k], 0.0));
  EXPECT_EQ(reprojection_rmse(s.map), before);
  // The solution: the first keyframe held, every other one back near the truth.
  double max_t = 0;
  for (const auto& [kf, T_cw] : result.keyframes) {
    const size_t k = static_cast<size_t>(kf->id);
    if (k == 0) {
      EXPECT_TRUE(T_cw.isApprox(poses[0], 0.0));
    }
    max_t = std::max(max_t, translation_between(T_cw.inverse(), s.truth[k].inverse()));
  }
  for (const auto& [kf, T_cw] : result.keyframes) kf->T_cw = T_cw;
  for (const auto& [mp, x] : result.points) mp->position = x;
  const double after = reprojection_rmse(s.map);
  std::printf("[global BA] rmse %.3f -> %.3f px, pose error max %.4f m\n", before, after, max_t);
  EXPECT_LT(max_t, 0.01);
  EXPECT_GT(before / after, 5.0);
}

TEST(GlobalBundleAdjustment, AbortedReturnsNothing) {
  BaScene s;
  build_ba_scene(s, 22);
  std::atomic<bool> abort{true};
  const GlobalBaResult result = global_bundle_adjustment(s.map, &abort, 10);
  EXPECT_FALSE(result.completed);
  EXPECT_TRUE(result.keyframes.empty());
  EXPECT_TRUE(s.map.mutex().try_lock());
  s.map.mutex().unlock();
}

TEST(GlobalBundleAdjustment, LeavesBadKeyframesAndPointsOut) {
  BaScene s;
  build_ba_scene(s, 23);
  s.kfs[3]->set_bad();
  s.map.erase_keyframe(s.kfs[3]);
  MapPoint* gone = *s.map.map_points().begin();
  gone->set_bad();
  s.map.erase_map_point(gone);
  const GlobalBaResult result = global_bundle_adjustment(s.map, nullptr, 5);
  ASSERT_TRUE(result.completed);
  for (const auto& [kf, T] : result.keyframes) EXPECT_NE(kf, s.kfs[3]);
  for (const auto& [mp, x] : result.points) EXPECT_NE(mp, gone);
  EXPECT_EQ(result.keyframes.size(), 4u);
}

}  // namespace
}  // namespace depot::slam
