#include "slam/optimize/optimizer.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "common/rng.h"
#include "slam/data/map_point.h"

namespace depot::slam {
namespace {

constexpr double kDeg = M_PI / 180.0;

const ScaleLevels& levels() {
  static const ScaleLevels lv = ScaleLevels::make(8, 1.2f);
  return lv;
}

// A rotation of `angle` rad about a random axis.
Eigen::Matrix3d random_rotation(Rng& rng, double angle) {
  Eigen::Vector3d axis(rng.normal(), rng.normal(), rng.normal());
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

Eigen::Vector3d random_direction(Rng& rng) {
  return Eigen::Vector3d(rng.normal(), rng.normal(), rng.normal()).normalized();
}

// T_cw perturbed by exactly `trans` m of camera-centre motion and `angle` rad.
Pose perturb(const Pose& T_cw, Rng& rng, double trans, double angle) {
  const Pose T_wc = T_cw.inverse();
  Pose out = make_pose(Eigen::Matrix3d(random_rotation(rng, angle) * T_wc.linear()),
                       Eigen::Vector3d(T_wc.translation() + trans * random_direction(rng)));
  return out.inverse();
}

// A camera looking roughly along +z from `center`, yawed by `yaw` rad.
Pose camera_pose(const Eigen::Vector3d& center, double yaw) {
  const Eigen::Matrix3d R_wc = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitY()).toRotationMatrix();
  return make_pose(R_wc, center).inverse();
}

struct Keypoint {
  double u, v, z;  // z <= 0: no depth
  int octave;
};

// Features filled directly from synthetic keypoints (depth -> u_right).
Features make_features(const std::vector<Keypoint>& kps, const PinholeCamera& cam) {
  Features f;
  f.camera = cam;
  f.levels = &levels();
  f.descriptors = cv::Mat::zeros(static_cast<int>(kps.size()), 32, CV_8U);
  for (const Keypoint& k : kps) {
    f.keypoints.emplace_back(static_cast<float>(k.u), static_cast<float>(k.v), 31.0f, -1.0f, 0.0f,
                             k.octave);
    f.depth.push_back(k.z > 0 ? static_cast<float>(k.z) : -1.0f);
    f.u_right.push_back(k.z > 0 ? static_cast<float>(cam.right_u(k.u, k.z)) : -1.0f);
  }
  return f;
}

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

struct BaScene {
  Map map;
  std::vector<KeyFrame*> kfs;
  std::vector<Pose> truth;
  // Per keyframe, the keypoint indices whose keypoint was made a gross outlier.
  std::vector<std::vector<size_t>> gross;
};

// 5 keyframes along a short sideways path observing 400 points; keyframe 0
// exact, the others perturbed by 2 cm / 1 deg, the points by 3 cm.
void build_ba_scene(BaScene& s, uint64_t seed, int n_gross_per_kf = 0) {
  Rng rng(seed);
  const PinholeCamera cam;
  constexpr int kKeyframes = 5, kPoints = 400;
  for (int k = 0; k < kKeyframes; ++k)
    s.truth.push_back(camera_pose(Eigen::Vector3d(0.15 * k, 0.02 * k, 0.05 * k), -0.03 * k));
  // Points in front of the middle camera, spread in depth.
  const Pose mid_wc = s.truth[kKeyframes / 2].inverse();
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < kPoints; ++i)
    points.push_back(mid_wc * cam.unproject(rng.uniform(60, cam.width - 60),
                                            rng.uniform(50, cam.height - 50),
                                            rng.uniform(1.5, 5.0)));

  std::vector<std::vector<int>> point_of(kKeyframes);  // per keyframe: point of each keypoint
  for (int k = 0; k < kKeyframes; ++k) {
    std::vector<Keypoint> kps;
    for (int i = 0; i < kPoints; ++i) {
      const Eigen::Vector3d pc = s.truth[k] * points[i];
      if (pc.z() <= 0.1) continue;
      const Eigen::Vector2d uv = cam.project(pc);
      if (!cam.in_image(uv.x(), uv.y())) continue;
      kps.push_back({uv.x() + rng.normal(0, 0.5), uv.y() + rng.normal(0, 0.5),
                     pc.z() * (1.0 + rng.normal(0, 0.002)), static_cast<int>(rng.below(3))});
      point_of[k].push_back(i);
    }
    s.gross.emplace_back();
    for (int g = 0; g < n_gross_per_kf; ++g) {
      const size_t idx = rng.below(kps.size());
      kps[idx].u += 40 * (rng.uniform() < 0.5 ? -1 : 1);
      kps[idx].v += 30;
      s.gross.back().push_back(idx);
    }
    Frame f(k, 0.1 * k, make_features(kps, cam));
    f.T_cw = k == 0 ? s.truth[0] : perturb(s.truth[k], rng, 0.02, 1 * kDeg);
    f.has_pose = true;
    s.kfs.push_back(s.map.create_keyframe(f));
  }
  std::vector<MapPoint*> mps;
  for (int i = 0; i < kPoints; ++i)
    mps.push_back(s.map.create_map_point(points[i] + 0.03 * random_direction(rng), s.kfs[0]));
  for (int k = 0; k < kKeyframes; ++k)
    for (size_t idx = 0; idx < point_of[k].size(); ++idx) {
      MapPoint* mp = mps[point_of[k][idx]];
      mp->add_observation(s.kfs[k], idx);
      s.kfs[k]->add_map_point(mp, idx);
    }
  for (MapPoint* mp : mps) {
    if (!mp->observations.count(mp->reference)) mp->reference = mp->observations.begin()->first;
    mp->update_normal_and_depth();
  }
  for (KeyFrame* kf : s.kfs) kf->update_connections();
}

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

}  // namespace
}  // namespace depot::slam
