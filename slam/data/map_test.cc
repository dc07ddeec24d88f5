// The atlas (map.h): maps begun on loss keep their own keyframes, points and
// origin; a merge moves one map rigidly into another's frame.
#include "slam/data/map.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

namespace depot::slam {
namespace {

KeyFrame* add_keyframe(Map& map, const Pose& T_cw) {
  Frame frame;
  frame.id = static_cast<long>(map.all_keyframes().size());
  frame.map_points.assign(4, nullptr);
  frame.T_cw = T_cw;
  return map.create_keyframe(frame);
}

Pose pose(double yaw, const Eigen::Vector3d& t) {
  Pose T = Pose::Identity();
  T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitY()).toRotationMatrix();
  T.translation() = t;
  return T;
}

TEST(Atlas, EachMapHasItsOwnKeyframesPointsAndOrigin) {
  Map map;
  KeyFrame* a0 = add_keyframe(map, Pose::Identity());
  KeyFrame* a1 = add_keyframe(map, pose(0.1, {0.2, 0, 0}));
  MapPoint* pa = map.create_map_point({0, 0, 3}, a1);
  EXPECT_EQ(map.active_map(), 0);
  const int second = map.begin_map();
  EXPECT_EQ(second, 1);
  EXPECT_EQ(map.active_map(), 1);
  KeyFrame* b0 = add_keyframe(map, Pose::Identity());
  MapPoint* pb = map.create_map_point({1, 0, 3}, b0);
  EXPECT_TRUE(a0->map_origin);
  EXPECT_FALSE(a1->map_origin);
  EXPECT_TRUE(b0->map_origin) << "the first keyframe of a new map is its origin";
  EXPECT_EQ(pa->map_id, 0);
  EXPECT_EQ(pb->map_id, 1);
  EXPECT_EQ(map.n_keyframes_in(0), 2u);
  EXPECT_EQ(map.n_keyframes_in(1), 1u);
  EXPECT_EQ(map.first_keyframe_in(1), b0);
  EXPECT_EQ(map.map_ids(), (std::vector<int>{0, 1}));
  map.activate(0);
  EXPECT_EQ(add_keyframe(map, Pose::Identity())->map_id, 0);
}

// Map 1 is map 0 seen from a frame turned and shifted by T_01: after the
// merge its keyframes and points sit where map 0 has them.
TEST(Atlas, AMergeMovesOneMapRigidlyIntoTheOthersFrame) {
  const Pose T_01 = pose(0.7, {1.5, -0.2, 0.4});         // map 1's frame into map 0's
  const Pose camera_in_0 = pose(-0.3, {0.5, 0.1, 2.0});  // a camera, T_cw in map 0
  const Eigen::Vector3d point_in_0(0.3, -0.4, 5.0);
  Map map;
  add_keyframe(map, Pose::Identity());
  map.begin_map();
  KeyFrame* b0 = add_keyframe(map, Pose::Identity());
  KeyFrame* b1 = add_keyframe(map, camera_in_0 * T_01);
  MapPoint* p = map.create_map_point(T_01.inverse() * point_in_0, b1);
  map.merge_maps(1, 0, T_01);
  EXPECT_EQ(b1->map_id, 0);
  EXPECT_EQ(p->map_id, 0);
  EXPECT_FALSE(b0->map_origin) << "one origin per map";
  EXPECT_EQ(map.map_ids(), (std::vector<int>{0}));
  EXPECT_EQ(map.active_map(), 0) << "the active map followed the merge";
  EXPECT_LT((b1->T_cw.matrix() - camera_in_0.matrix()).norm(), 1e-12);
  EXPECT_LT((p->position - point_in_0).norm(), 1e-12);
  // A keyframe sees the point where it saw it before the merge.
  EXPECT_LT((b0->T_cw * p->position - T_01.inverse() * point_in_0).norm(), 1e-12);
}

TEST(Atlas, DiscardingAMapLeavesTheOthersAsTheyWere) {
  Map map;
  KeyFrame* a0 = add_keyframe(map, Pose::Identity());
  MapPoint* pa = map.create_map_point({0, 0, 3}, a0);
  map.begin_map();
  KeyFrame* b0 = add_keyframe(map, Pose::Identity());
  KeyFrame* b1 = add_keyframe(map, pose(0.1, {0.2, 0, 0}));
  MapPoint* pb = map.create_map_point({1, 0, 3}, b1);
  EXPECT_EQ(map.discard_map(1), (std::vector<KeyFrame*>{b0, b1}));
  EXPECT_TRUE(b0->bad && b1->bad && pb->bad);
  EXPECT_FALSE(a0->bad || pa->bad);
  EXPECT_EQ(map.map_ids(), (std::vector<int>{0}));
  EXPECT_EQ(map.n_keyframes(), 1u);
  EXPECT_EQ(map.n_map_points(), 1u);
}

}  // namespace
}  // namespace depot::slam
