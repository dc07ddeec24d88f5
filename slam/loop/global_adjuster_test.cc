#include "slam/loop/global_adjuster.h"

#include <algorithm>
#include <cstdio>

#include <gtest/gtest.h>

#include "slam/data/map_point.h"
#include "slam/mapping/local_mapper.h"
#include "tests/support/ba_scene.h"

namespace depot::slam {
namespace {

using namespace depot::slam::test;

double max_pose_error(const BaScene& s) {
  double max_t = 0;
  for (size_t k = 0; k < s.kfs.size(); ++k)
    max_t = std::max(max_t, translation_between(s.kfs[k]->T_cw.inverse(), s.truth[k].inverse()));
  return max_t;
}

TEST(GlobalAdjuster, ThreadedAdjustmentIsAppliedToTheMap) {
  BaScene s;
  build_ba_scene(s, 31);
  const double before = reprojection_rmse(s.map), error_before = max_pose_error(s);
  LocalMapper mapper(s.map, true);
  GlobalAdjuster adjuster(s.map, mapper, true, 10);
  adjuster.start();
  adjuster.wait();
  EXPECT_FALSE(adjuster.running());
  EXPECT_EQ(adjuster.completed(), 1);
  EXPECT_FALSE(adjuster.failure());
  MutexLock lock(s.map.mutex());
  const double after = reprojection_rmse(s.map), error_after = max_pose_error(s);
  std::printf("[global adjuster] rmse %.3f -> %.3f px, pose error %.4f -> %.4f m\n", before, after,
              error_before, error_after);
  EXPECT_GT(before / after, 5.0);
  EXPECT_LT(error_after, 0.01);
}

TEST(GlobalAdjuster, SynchronousModeAdjustsInsideStart) {
  BaScene s;
  build_ba_scene(s, 32);
  LocalMapper mapper(s.map, false);
  GlobalAdjuster adjuster(s.map, mapper, false, 10);
  adjuster.start();
  EXPECT_EQ(adjuster.completed(), 1);
  EXPECT_LT(max_pose_error(s), 0.01);
}

// What the map gained while the adjustment solved moves with it.
TEST(GlobalAdjuster, KeyFramesAndPointsMadeMeanwhileFollowTheirParentAndReference) {
  BaScene s;
  build_ba_scene(s, 33);
  GlobalBaResult result = global_bundle_adjustment(s.map, nullptr, 10);
  ASSERT_TRUE(result.completed);
  // Pretend the last keyframe and the points it references were made after
  // the problem was collected.
  KeyFrame* late = s.kfs.back();
  // A parent the adjustment moves (the first keyframe is held fixed).
  KeyFrame* parent = s.kfs[3];
  late->set_parent(parent);
  result.keyframes.erase(std::remove_if(result.keyframes.begin(), result.keyframes.end(),
                                        [&](const auto& r) { return r.first == late; }),
                         result.keyframes.end());
  MapPoint* late_point = *s.map.map_points().rbegin();
  late_point->reference = late;
  result.points.erase(std::remove_if(result.points.begin(), result.points.end(),
                                     [&](const auto& r) { return r.first == late_point; }),
                      result.points.end());
  Pose parent_after = Pose::Identity();
  for (const auto& [kf, T] : result.keyframes)
    if (kf == parent) parent_after = T;
  const Pose parent_before = parent->T_cw;
  const Pose late_relative = late->T_cw * parent->T_cw.inverse();
  const Eigen::Vector3d late_point_in_camera = late->T_cw * late_point->position;
  {
    MutexLock lock(s.map.mutex());
    apply_global_adjustment(s.map, result);
  }
  EXPECT_TRUE(parent->T_cw.isApprox(parent_after, 1e-12));
  EXPECT_FALSE(parent_after.isApprox(parent_before, 1e-6)) << "the parent must move";
  // Same pose relative to its parent, the point at the same place in its camera.
  EXPECT_TRUE((late->T_cw * parent->T_cw.inverse()).isApprox(late_relative, 1e-9));
  EXPECT_LT((late->T_cw * late_point->position - late_point_in_camera).norm(), 1e-9);
  // And the solved ones are the result.
  for (const auto& [mp, x] : result.points) EXPECT_EQ(mp->position, x);
}

TEST(GlobalAdjuster, AbortDropsTheResult) {
  BaScene s;
  build_ba_scene(s, 34);
  std::vector<Pose> poses;
  for (const KeyFrame* kf : s.kfs) poses.push_back(kf->T_cw);
  LocalMapper mapper(s.map, true);
  GlobalAdjuster adjuster(s.map, mapper, true, 10000);
  adjuster.start();
  adjuster.abort();
  EXPECT_FALSE(adjuster.running());
  EXPECT_EQ(adjuster.completed(), 0);
  for (size_t k = 0; k < s.kfs.size(); ++k) EXPECT_TRUE(s.kfs[k]->T_cw.isApprox(poses[k], 0.0));
}

}  // namespace
}  // namespace depot::slam
