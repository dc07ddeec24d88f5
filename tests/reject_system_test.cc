// Rejection inside the running system on a rendered walking scene: `full`
// with the simulated detector (its default, calibrated to Yolo-Fastest) must beat plain ORB-SLAM2
// by a wide margin, and its rejected points must be scored against the
// simulator's ground truth.
#include <gtest/gtest.h>

#include "eval/improvement.h"
#include "tests/support/render_helpers.h"
#include "tests/support/slam_helpers.h"

namespace depot::test {
namespace {

TEST(RejectSystem, FullModeBeatsPlainOrbOnWalkingPeople) {
  std::string data = render_small({"depot_walking_xyz", 200, 640, false});
  SlamOutcome orb = run_slam_mode(data, slam::RejectionMode::kOrb, true);
  SlamOutcome full = run_slam_mode(data, slam::RejectionMode::kFull, false);
  SlamOutcome yolo = run_slam_mode(data, slam::RejectionMode::kOrbYolo, false);
  const double rho = eval::improvement_percent(orb.ate_rmse, full.ate_rmse);
  std::printf(
      "walking_xyz 200 frames: ATE orb %.4f, orb+yolo %.4f, full %.4f m (improvement %.1f %%); "
      "full "
      "precision %.3f recall %.3f\n",
      orb.ate_rmse, yolo.ate_rmse, full.ate_rmse, rho, full.score.precision(), full.score.recall());
  EXPECT_LT(full.ate_rmse, 0.03);
  EXPECT_GT(rho, 80.0);
  // Frames where people cover much of the view are lost and relocalised at
  // once: with the earlier generic error model two (192, 194); with the
  // default calibrated to Yolo-Fastest (larger box errors, desks and chairs
  // never found) eight (24, 43, 182-196 every other frame; ATE unchanged).
  EXPECT_LE(full.lost, 8);
  // The rejected points are mostly on moving people (recall), even though box-level
  // rejection also throws away background inside the boxes (precision). The
  // mesh people are slimmer than the primitive ones, so their boxes hold
  // more background: precision 0.24 here (0.30-0.35 with primitives).
  EXPECT_GT(full.score.recall(), 0.8);
  EXPECT_GT(full.score.precision(), 0.2);

  // Our depth split of the boxes (off in the paper's full) keeps the
  // background the boxes enclose: far fewer static points thrown away, for
  // a small loss of recall, and tracking as good.
  slam::RejectionParams split;
  split.background_depth_margin = 0.4f;
  SlamOutcome depth = run_slam_mode(data, slam::RejectionMode::kFull, false, split);
  std::printf("full with the depth split: ATE %.4f m, precision %.3f recall %.3f\n", depth.ate_rmse,
              depth.score.precision(), depth.score.recall());
  EXPECT_GT(depth.score.precision(), full.score.precision() + 0.2);
  EXPECT_GT(depth.score.recall(), full.score.recall() - 0.1);
  EXPECT_LT(depth.score.false_positive, full.score.false_positive / 3);
  EXPECT_LT(depth.ate_rmse, 0.03);
  EXPECT_EQ(depth.lost, 0);
}

}  // namespace
}  // namespace depot::test
