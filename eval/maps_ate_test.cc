// ATE over every map of the atlas, each aligned on its own (maps_ate.h).
#include "eval/maps_ate.h"

#include <gtest/gtest.h>

#include "common/error.h"
#include "eval/ate.h"
#include "eval/matched_trajectories.h"
#include "eval/test_trajectories.h"

namespace depot::eval {
namespace {

using testing::deg;
using testing::helix_trajectory;
using testing::moved;
using testing::rotation_about;

MapsAte maps_ate(const std::vector<StampedPose>& gt, const std::vector<StampedPose>& atlas,
                 const std::vector<int>& maps, size_t frames) {
  return compute_maps_ate(gt, atlas, maps, frames, {}, AlignmentKind::kRigid, "gt.txt",
                          "run.atlas.txt");
}

// Three maps of one exact run, each in a world frame of its own, and a
// lost stretch between them: every map aligns to zero error, while one
// alignment of all poses cannot.
TEST(MapsAte, EachMapIsAlignedOnItsOwn) {
  const std::vector<StampedPose> gt = helix_trajectory(300, 30.0);
  std::vector<StampedPose> atlas;
  std::vector<int> maps;
  const Pose frames_of[3] = {rotation_about({0, 0, 1}, deg(40), {1, 2, 0}),
                             rotation_about({1, 0, 1}, deg(-75), {0, -3, 1}),
                             rotation_about({0, 1, 0}, deg(10), {2, 0, 0})};
  for (size_t k = 0; k < gt.size(); ++k) {
    if (k >= 100 && k < 120) continue;  // lost: no pose
    const int map = k < 100 ? 1 : k < 290 ? 0 : 2;
    atlas.push_back({gt[k].timestamp, frames_of[map] * gt[k].pose});
    maps.push_back(map);
  }
  const MapsAte r = maps_ate(gt, atlas, maps, gt.size());
  EXPECT_EQ(r.maps, 3u);
  EXPECT_EQ(r.maps_left_out, 0u);
  EXPECT_EQ(r.posed, 280u);
  EXPECT_EQ(r.in_main_map, 170u);
  EXPECT_EQ(r.statistics.count, 280u);
  EXPECT_LT(r.statistics.rmse, 1e-9);
  EXPECT_NEAR(r.posed_share(), 280.0 / 300.0, 1e-12);
  EXPECT_NEAR(r.main_map_share(), 170.0 / 300.0, 1e-12);
  // The same poses as if they were one map: far off.
  const AteResult one = compute_ate(match_trajectories(gt, atlas, {}, "gt.txt", "atlas"));
  EXPECT_GT(one.statistics.rmse, 0.5);
}

// A map of two poses cannot be aligned: it is counted, not scored; the
// errors of the others are theirs.
TEST(MapsAte, AMapTooSmallToAlignIsCountedAsLeftOut) {
  const std::vector<StampedPose> gt = helix_trajectory(50, 30.0);
  std::vector<StampedPose> atlas;
  std::vector<int> maps;
  for (size_t k = 0; k < gt.size(); ++k) {
    StampedPose p = gt[k];
    p.pose.translation().z() += k % 2 ? 0.01 : -0.01;
    atlas.push_back(p);
    maps.push_back(k < 2 ? 1 : 0);
  }
  const MapsAte r = maps_ate(gt, moved(atlas, rotation_about({1, 1, 0}, deg(30))), maps, 60);
  EXPECT_EQ(r.maps, 2u);
  EXPECT_EQ(r.maps_left_out, 1u);
  EXPECT_EQ(r.poses_left_out, 2u);
  EXPECT_EQ(r.posed, 50u);
  EXPECT_EQ(r.statistics.count, 48u);
  EXPECT_NEAR(r.statistics.rmse, 0.01, 1e-3);
}

TEST(MapsAte, MismatchedInputsAreOneError) {
  const std::vector<StampedPose> gt = helix_trajectory(10, 30.0);
  EXPECT_THROW(maps_ate(gt, gt, std::vector<int>(9, 0), 10), Error);
  try {
    maps_ate(gt, gt, std::vector<int>(10, 1), 10);
    FAIL() << "no map 0";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "run.atlas.txt: has no pose in map 0 (the trajectory's)");
  }
}

}  // namespace
}  // namespace depot::eval
