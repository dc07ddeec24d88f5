// Covisibility graph and spanning tree of keyframes, built directly from
// keyframes and shared map points (no images needed: update_connections
// only counts shared observations).
#include "slam/data/keyframe.h"

#include <gtest/gtest.h>

#include "slam/data/map.h"

namespace depot::slam {
namespace {

constexpr size_t kSlots = 200;  // keypoint slots of every keyframe

// A keyframe at camera centre (x, 0, 0) with kSlots empty map point slots.
KeyFrame* add_keyframe(Map& map, double x) {
  Frame frame;
  frame.id = static_cast<long>(map.all_keyframes().size());
  frame.map_points.assign(kSlots, nullptr);
  frame.T_cw = Pose::Identity();
  frame.T_cw.translation() = Eigen::Vector3d(-x, 0, 0);
  return map.create_keyframe(frame);
}

// `n` new points seen by every keyframe in `kfs`, in slots from `first` on.
void share_points(Map& map, const std::vector<KeyFrame*>& kfs, size_t first, size_t n) {
  for (size_t k = 0; k < n; ++k) {
    MapPoint* mp = map.create_map_point(Eigen::Vector3d(0, 0, 5), kfs.front());
    for (KeyFrame* kf : kfs) {
      mp->add_observation(kf, first + k);
      kf->add_map_point(mp, first + k);
    }
  }
}

TEST(Covisibility, KeepsNeighboursSharingAtLeastFifteenPointsWithSymmetricWeights) {
  Map map;
  KeyFrame* a = add_keyframe(map, 0);
  KeyFrame* b = add_keyframe(map, 1);
  KeyFrame* c = add_keyframe(map, 2);
  KeyFrame* d = add_keyframe(map, 3);
  share_points(map, {a, b}, 0, 20);
  share_points(map, {a, c}, 20, 14);
  share_points(map, {a, d}, 40, 15);
  a->update_connections();
  EXPECT_EQ(a->weight(b), 20);
  EXPECT_EQ(a->weight(c), 0) << "14 shared points are below the threshold";
  EXPECT_EQ(a->weight(d), 15);
  // The neighbours learn the link too.
  EXPECT_EQ(b->weight(a), 20);
  EXPECT_EQ(d->weight(a), 15);
  EXPECT_EQ(c->weight(a), 0);
}

TEST(Covisibility, WithNoNeighbourAtFifteenTheBestOneIsKept) {
  Map map;
  KeyFrame* a = add_keyframe(map, 0);
  KeyFrame* b = add_keyframe(map, 1);
  KeyFrame* c = add_keyframe(map, 2);
  share_points(map, {a, b}, 0, 5);
  share_points(map, {a, c}, 5, 7);
  a->update_connections();
  EXPECT_EQ(a->covisibles(), std::vector<KeyFrame*>{c});
  EXPECT_EQ(a->weight(c), 7);
  EXPECT_EQ(a->weight(b), 0);
}

TEST(Covisibility, NeighboursAreOrderedByWeightThenId) {
  Map map;
  KeyFrame* a = add_keyframe(map, 0);
  KeyFrame* b = add_keyframe(map, 1);
  KeyFrame* c = add_keyframe(map, 2);
  KeyFrame* d = add_keyframe(map, 3);
  KeyFrame* e = add_keyframe(map, 4);
  share_points(map, {a, b}, 0, 16);
  share_points(map, {a, c}, 16, 40);
  share_points(map, {a, d}, 56, 25);
  share_points(map, {a, e}, 81, 25);  // ties with d: the lower id first
  a->update_connections();
  EXPECT_EQ(a->covisibles(), (std::vector<KeyFrame*>{c, d, e, b}));
  EXPECT_EQ(a->covisibles(2), (std::vector<KeyFrame*>{c, d}));
  EXPECT_EQ(a->covisibles_with_weight(25), (std::vector<KeyFrame*>{c, d, e}));
  // Bad keyframes are skipped.
  d->set_bad();
  EXPECT_EQ(a->covisibles(), (std::vector<KeyFrame*>{c, e, b}));
}

TEST(Covisibility, BadPointsAndBadKeyframesDoNotCount) {
  Map map;
  KeyFrame* a = add_keyframe(map, 0);
  KeyFrame* b = add_keyframe(map, 1);
  share_points(map, {a, b}, 0, 20);
  for (size_t i = 0; i < 6; ++i) a->map_points[i]->bad = true;
  a->update_connections();
  EXPECT_EQ(a->weight(b), 14) << "the best neighbour is kept, with its real weight";
}

TEST(SpanningTree, TheFirstConnectionMakesTheMostCovisibleKeyframeTheParent) {
  Map map;
  KeyFrame* root = add_keyframe(map, 0);
  KeyFrame* a = add_keyframe(map, 1);
  KeyFrame* b = add_keyframe(map, 2);
  share_points(map, {root, a}, 0, 30);
  share_points(map, {root, b}, 30, 20);
  share_points(map, {a, b}, 50, 25);
  root->update_connections();
  EXPECT_EQ(root->parent(), nullptr) << "the first keyframe is the root";
  a->update_connections();
  b->update_connections();
  EXPECT_EQ(a->parent(), root);
  EXPECT_EQ(b->parent(), a) << "a shares 25 points with b, root only 20";
  EXPECT_EQ(root->children().count(a), 1u);
  EXPECT_EQ(a->children().count(b), 1u);
  // The parent is chosen once: later connections do not move it.
  share_points(map, {root, b}, 75, 50);
  b->update_connections();
  EXPECT_EQ(b->parent(), a);
}

TEST(SpanningTree, SetBadHandsChildrenToTheParentAndKeepsThePoseRelativeToIt) {
  Map map;
  KeyFrame* root = add_keyframe(map, 0);
  KeyFrame* mid = add_keyframe(map, 1);
  KeyFrame* leaf = add_keyframe(map, 2);
  share_points(map, {root, mid}, 0, 30);
  share_points(map, {mid, leaf}, 30, 30);
  share_points(map, {root, leaf}, 60, 16);
  root->update_connections();
  mid->update_connections();
  leaf->update_connections();
  ASSERT_EQ(leaf->parent(), mid);
  mid->T_cw.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Pose mid_T_cw = mid->T_cw;

  mid->set_bad();
  EXPECT_TRUE(mid->bad);
  EXPECT_EQ(leaf->parent(), root);
  EXPECT_EQ(root->children().count(leaf), 1u);
  EXPECT_EQ(root->children().count(mid), 0u);
  EXPECT_TRUE(mid->children().empty());
  // The culled keyframe's pose stays reachable through its parent (what
  // trajectory resolution uses): T_cw = T_cp * parent.T_cw.
  EXPECT_TRUE((mid->T_cp * root->T_cw).isApprox(mid_T_cw, 1e-12));
  // It leaves the covisibility graph and its points' observations.
  EXPECT_EQ(root->weight(mid), 0);
  EXPECT_EQ(leaf->weight(mid), 0);
  EXPECT_TRUE(mid->covisibles().empty());
  for (MapPoint* mp : root->map_points) {
    if (mp) {
      EXPECT_EQ(mp->observations.count(mid), 0u);
    }
  }
  // The root cannot be removed.
  root->set_bad();
  EXPECT_FALSE(root->bad);
}

}  // namespace
}  // namespace depot::slam
