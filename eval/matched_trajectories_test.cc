#include "eval/matched_trajectories.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/error.h"
#include "common/testing/error_of.h"
#include "eval/test_trajectories.h"

namespace depot::eval {
namespace {

using testing::helix_trajectory;
using testing::write_scratch_file;

TEST(MatchedTrajectories, KeepsOnlyPosesWithPartners) {
  const auto gt = helix_trajectory(50, 100.0);  // 0.5 s at 100 Hz
  std::vector<StampedPose> est;
  for (size_t k = 0; k < gt.size(); k += 5) est.push_back({gt[k].timestamp + 0.003, gt[k].pose});
  est.push_back({gt.back().timestamp + 1.0, Pose::Identity()});  // after the end: dropped
  const MatchedTrajectories m = match_trajectories(gt, est, {}, "gt.txt", "est.txt");
  ASSERT_EQ(m.size(), 10u);
  EXPECT_EQ(m.reference_size, 50u);
  EXPECT_EQ(m.estimate_size, 11u);
  for (size_t k = 0; k < m.size(); ++k) {
    EXPECT_DOUBLE_EQ(m.reference_stamps[k], gt[5 * k].timestamp);
    EXPECT_DOUBLE_EQ(m.estimate_stamps[k], gt[5 * k].timestamp + 0.003);
    EXPECT_TRUE(m.reference[k].isApprox(m.estimate[k]));
  }
}

TEST(MatchedTrajectories, NoOverlapNamesBothFiles) {
  const auto gt = helix_trajectory(20, 10.0, 100.0);
  const auto est = helix_trajectory(20, 10.0, 500.0);
  const std::string message =
      error_of([&] { match_trajectories(gt, est, {}, "gt.txt", "est.txt"); });
  EXPECT_EQ(message.rfind("est.txt: no timestamp lies within 0.02 s of ground truth gt.txt", 0), 0u)
      << message;
}

TEST(MatchedTrajectories, FewerThanThreePairsIsAnError) {
  const auto gt = helix_trajectory(20, 10.0, 100.0);
  const std::vector<StampedPose> est = {gt[3], gt[7]};
  const std::string message =
      error_of([&] { match_trajectories(gt, est, {}, "gt.txt", "est.txt"); });
  EXPECT_THAT(message, ::testing::HasSubstr("est.txt: only 2 timestamps match (need at least 3)"))
      << message;
  const std::vector<StampedPose> three = {gt[3], gt[7], gt[9]};
  EXPECT_EQ(match_trajectories(gt, three, {}, "gt.txt", "est.txt").size(), 3u);
}

TEST(MatchedTrajectories, FileErrorsNameTheFile) {
  const std::string good =
      write_scratch_file("good.txt",
                         "# t x y z qx qy qz qw\n1.0 0 0 0 0 0 0 1\n1.1 0 0 0 0 0 0 1\n"
                         "1.2 0 0 0 0 0 0 1\n");
  const std::string malformed =
      write_scratch_file("malformed.txt", "1.0 0 0 0 0 0 0 1\n1.1 0 zero 0 0 0 0 1\n");
  const std::string with_nan =
      write_scratch_file("nan.txt", "1.0 0 0 0 0 0 0 1\n1.1 0 0 nan 0 0 0 1\n");
  const std::string missing = testing::scratch_path("does_not_exist.txt");

  EXPECT_NO_THROW(load_matched_trajectories(good, good));
  EXPECT_EQ(error_of([&] { load_matched_trajectories(missing, good); }),
            missing + ": cannot open file");
  EXPECT_EQ(
      error_of([&] { load_matched_trajectories(good, malformed); }).rfind(malformed + ":2:", 0),
      0u);
  EXPECT_EQ(error_of([&] { load_matched_trajectories(good, with_nan); }).rfind(with_nan + ":2:", 0),
            0u);
}

}  // namespace
}  // namespace depot::eval
