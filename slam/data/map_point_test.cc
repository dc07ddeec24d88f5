// Fusing map points: replace() hands observations to the survivor, and
// follow_replacements() leads holders of the fused point to it.
#include "slam/data/map_point.h"

#include <gtest/gtest.h>

#include "slam/data/map.h"

namespace depot::slam {
namespace {

KeyFrame* add_keyframe(Map& map) {
  Frame frame;
  frame.id = static_cast<long>(map.all_keyframes().size());
  frame.map_points.assign(10, nullptr);
  // Descriptors: fusion picks the survivor's representative one.
  frame.features.descriptors = cv::Mat(10, 32, CV_8U);
  cv::randu(frame.features.descriptors, 0, 256);
  return map.create_keyframe(frame);
}

MapPoint* add_point(Map& map, std::vector<std::pair<KeyFrame*, size_t>> seen_by) {
  MapPoint* mp = map.create_map_point(Eigen::Vector3d(0, 0, 4), seen_by.front().first);
  for (auto [kf, slot] : seen_by) {
    mp->add_observation(kf, slot);
    kf->add_map_point(mp, slot);
  }
  return mp;
}

TEST(MapPointFusion, ReplaceHandsObservationsToTheSurvivor) {
  Map map;
  KeyFrame* a = add_keyframe(map);
  KeyFrame* b = add_keyframe(map);
  KeyFrame* c = add_keyframe(map);
  MapPoint* fused = add_point(map, {{a, 1}, {b, 2}});
  MapPoint* survivor = add_point(map, {{b, 3}, {c, 4}});
  fused->replace(survivor);
  EXPECT_TRUE(fused->bad);
  EXPECT_EQ(fused->replaced_by, survivor);
  EXPECT_EQ(a->map_points[1], survivor);
  EXPECT_EQ(survivor->observations.at(a), 1u);
  // b saw both: it keeps the survivor's own slot and drops the other.
  EXPECT_EQ(b->map_points[2], nullptr);
  EXPECT_EQ(b->map_points[3], survivor);
  EXPECT_EQ(survivor->n_observations(), 3);
}

TEST(MapPointFusion, FollowReplacementsLeadsToTheLastSurvivor) {
  Map map;
  KeyFrame* a = add_keyframe(map);
  KeyFrame* b = add_keyframe(map);
  MapPoint* first = add_point(map, {{a, 0}, {b, 0}});
  MapPoint* second = add_point(map, {{a, 1}, {b, 1}});
  MapPoint* third = add_point(map, {{a, 2}, {b, 2}});
  EXPECT_EQ(follow_replacements(first), first) << "a good point stands for itself";
  first->replace(second);
  second->replace(third);
  EXPECT_EQ(follow_replacements(first), third);
  EXPECT_EQ(follow_replacements(second), third);
  // A chain that ends in a culled point leads nowhere.
  third->set_bad();
  EXPECT_EQ(follow_replacements(first), nullptr);
  EXPECT_EQ(follow_replacements(nullptr), nullptr);
}

}  // namespace
}  // namespace depot::slam
