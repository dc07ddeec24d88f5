#include "eval/rpe.h"

#include <cmath>

#include <gtest/gtest.h>

#include "common/error.h"
#include "eval/test_trajectories.h"

namespace depot::eval {
namespace {

using testing::deg;
using testing::helix_trajectory;
using testing::moved;
using testing::rotation_about;

MatchedTrajectories match(const std::vector<StampedPose>& gt, const std::vector<StampedPose>& est) {
  return match_trajectories(gt, est, {}, "gt.txt", "est.txt");
}

std::vector<std::pair<size_t, size_t>> index_pairs(const std::vector<PosePair>& pairs) {
  std::vector<std::pair<size_t, size_t>> out;
  for (const PosePair& p : pairs) out.emplace_back(p.i, p.j);
  return out;
}

TEST(RelativePoseError, FollowsTheEvoFormula) {
  // E = (Q_i^-1 Q_j)^-1 (P_i^-1 P_j): with both motions starting from the
  // same turned pose, E is the difference of the motions in the start frame.
  const Pose start = rotation_about({0, 0, 1}, deg(90), {3, 4, 5});
  const Pose q_j = start * make_pose(Eigen::Matrix3d::Identity(), {1.0, 0.0, 0.0});
  const Pose p_j = start * make_pose(Eigen::Matrix3d::Identity(), {1.0, 0.0, 0.2});
  const Pose e = relative_pose_error(start, q_j, start, p_j);
  EXPECT_TRUE(e.translation().isApprox(Eigen::Vector3d(0.0, 0.0, 0.2), 1e-12));
  EXPECT_NEAR(rotation_angle_deg(e), 0.0, 1e-12);
  // When the motions turn differently the order matters: E is expressed in
  // the frame reached by the true motion (a right-hand difference would give
  // |t| = 0.0752 here).
  const Pose q_turn = rotation_about({0, 0, 1}, deg(90), {1.0, 0.0, 0.0});
  const Pose p_turn = rotation_about({0, 0, 1}, deg(100), {1.0, 0.1, 0.0});
  const Pose e_turn = relative_pose_error(Pose::Identity(), q_turn, Pose::Identity(), p_turn);
  EXPECT_TRUE(e_turn.translation().isApprox(Eigen::Vector3d(0.1, 0.0, 0.0), 1e-12));
  EXPECT_NEAR(rotation_angle_deg(e_turn), 10.0, 1e-9);
  EXPECT_NEAR(rotation_angle_deg(rotation_about({1, 1, 0}, deg(170))), 170.0, 1e-9);
  EXPECT_NEAR(rotation_angle_deg(rotation_about({1, 1, 0}, deg(-30))), 30.0, 1e-9);
  EXPECT_NEAR(rotation_angle_deg(rotation_about({0, 1, 0}, 1e-7)), 1e-7 * 180.0 / M_PI, 1e-15);
}

// The estimate drifts 1 cm per second along world x on top of a moving,
// turning ground truth: every 1 s pair is off by exactly 1 cm, 0 deg.
TEST(Rpe, ConstantTranslationDriftIsExact) {
  const auto gt = helix_trajectory(101, 10.0);  // 10 s at 10 Hz
  std::vector<StampedPose> est = gt;
  for (StampedPose& p : est) {
    p.pose.translation().x() += 0.01 * (p.timestamp - gt.front().timestamp);
  }
  const MatchedTrajectories m = match(gt, est);

  const RpeResult seconds = compute_rpe(m, {1.0, DeltaUnit::kSeconds});
  EXPECT_EQ(seconds.pairs.size(), 91u);
  EXPECT_NEAR(seconds.translation_statistics.min, 0.01, 1e-12);
  EXPECT_NEAR(seconds.translation_statistics.max, 0.01, 1e-12);
  EXPECT_NEAR(seconds.translation_statistics.rmse, 0.01, 1e-12);
  EXPECT_NEAR(seconds.translation_statistics.std, 0.0, 1e-12);
  EXPECT_LT(seconds.rotation_statistics.max, 1e-9);

  const RpeResult frames = compute_rpe(m, {10.0, DeltaUnit::kFrames});
  EXPECT_EQ(index_pairs(frames.pairs), index_pairs(seconds.pairs));
  EXPECT_NEAR(frames.translation_statistics.rmse, 0.01, 1e-12);

  const RpeResult two_seconds = compute_rpe(m, {2.0, DeltaUnit::kSeconds});
  EXPECT_NEAR(two_seconds.translation_statistics.rmse, 0.02, 1e-12);
}

// The estimate's camera turns 1 deg per second more than the ground truth
// about its own z axis (the ground truth turns about z, standing still).
TEST(Rpe, ConstantRotationDriftIsExact) {
  std::vector<StampedPose> gt, est;
  for (int k = 0; k <= 100; ++k) {
    const double t = 0.1 * k;
    const Pose truth = rotation_about({0, 0, 1}, deg(20.0 * t), {1.0, 2.0, 0.5});
    gt.push_back({t, truth});
    est.push_back({t, truth * rotation_about({0, 0, 1}, deg(1.0 * t))});
  }
  const RpeResult rpe = compute_rpe(match(gt, est), {1.0, DeltaUnit::kSeconds});
  EXPECT_NEAR(rpe.rotation_statistics.min, 1.0, 1e-9);
  EXPECT_NEAR(rpe.rotation_statistics.max, 1.0, 1e-9);
  EXPECT_NEAR(rpe.rotation_statistics.rmse, 1.0, 1e-9);
  EXPECT_LT(rpe.translation_statistics.max, 1e-12);
}

TEST(Rpe, UnchangedWhenEitherTrajectoryIsMovedRigidly) {
  const auto gt = helix_trajectory(120, 30.0);
  std::vector<StampedPose> est = gt;
  for (size_t k = 0; k < est.size(); ++k) {  // some irregular error
    est[k].pose = est[k].pose * rotation_about({1, 0, 1}, deg(0.5 * std::sin(0.3 * k)),
                                               {0.01 * std::cos(0.7 * k), 0.004 * k / 120.0, 0});
  }
  const RpeResult a = compute_rpe(match(gt, est));
  const RpeResult b =
      compute_rpe(match(gt, moved(est, rotation_about({0.3, 1, 0}, deg(75), {4, -1, 2}))));
  ASSERT_EQ(a.pairs.size(), b.pairs.size());
  EXPECT_NEAR(a.translation_statistics.rmse, b.translation_statistics.rmse, 1e-12);
  EXPECT_NEAR(a.rotation_statistics.rmse, b.rotation_statistics.rmse, 1e-9);
  EXPECT_GT(a.translation_statistics.rmse, 0.001);
}

TEST(RpePairs, SecondsPickTheClosestStampWithinTolerance) {
  const std::vector<double> stamps = {0.0, 0.3, 0.9, 1.05, 1.6, 1.93};
  // 0 -> 1.05 (target 1.0, off by 0.05); 0.3 -> none (1.3 is 0.25 from 1.05);
  // 0.9 -> 1.93 (off 0.03); later targets lie past the end.
  PairSelection selection{1.0, DeltaUnit::kSeconds};
  selection.max_time_error = 0.1;
  const std::vector<std::pair<size_t, size_t>> expected = {{0, 3}, {2, 5}};
  EXPECT_EQ(index_pairs(select_pose_pairs(stamps, selection)), expected);
}

TEST(RpePairs, SecondsDefaultAcceptsOnlyTheFrameNearestTheTarget) {
  std::vector<double> stamps;
  for (int k = 0; k <= 100; ++k) stamps.push_back(1e9 + 0.1 * k);  // 10 Hz, large epoch
  stamps.erase(stamps.begin() + 50, stamps.begin() + 53);          // a 0.4 s tracking gap
  const std::vector<PosePair> pairs = select_pose_pairs(stamps, {1.0, DeltaUnit::kSeconds});
  for (const PosePair& p : pairs) EXPECT_NEAR(stamps[p.j] - stamps[p.i], 1.0, 1e-6);
  // 98 poses; the last 10 have no partner 1 s later; targets at 5.0, 5.1
  // and 5.2 s fall in the gap (no frame within 0.05 s).
  EXPECT_EQ(pairs.size(), 98u - 10u - 3u);
}

TEST(RpePairs, FramesStartAPairAtEveryPose) {
  const std::vector<double> stamps = {0, 1, 2, 3, 4};
  const std::vector<std::pair<size_t, size_t>> expected = {{0, 2}, {1, 3}, {2, 4}};
  EXPECT_EQ(index_pairs(select_pose_pairs(stamps, {2.0, DeltaUnit::kFrames})), expected);
  EXPECT_TRUE(select_pose_pairs(stamps, {5.0, DeltaUnit::kFrames}).empty());
  EXPECT_TRUE(select_pose_pairs(stamps, {1e30, DeltaUnit::kFrames}).empty());
}

TEST(RpePairs, RejectsBadDeltas) {
  const std::vector<double> stamps = {0, 1, 2};
  EXPECT_THROW(select_pose_pairs(stamps, {0.0, DeltaUnit::kSeconds}), Error);
  EXPECT_THROW(select_pose_pairs(stamps, {-1.0, DeltaUnit::kFrames}), Error);
  EXPECT_THROW(select_pose_pairs(stamps, {1.5, DeltaUnit::kFrames}), Error);
  EXPECT_THROW(select_pose_pairs(stamps, {NAN, DeltaUnit::kSeconds}), Error);
}

TEST(Rpe, NoPairsNamesTheEstimate) {
  const auto gt = helix_trajectory(10, 10.0);  // 0.9 s long
  try {
    compute_rpe(match(gt, gt), {5.0, DeltaUnit::kSeconds});
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("est.txt: no pose pairs 5 s apart", 0), 0u) << e.what();
  }
}

}  // namespace
}  // namespace depot::eval
