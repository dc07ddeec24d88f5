// Rejection inside the running system on a rendered walking scene: `full`
// with the simulated detector (default error level) must beat plain ORB-SLAM2
// by a wide margin, and its rejected points must be scored against the
// simulator's ground truth.
#include <gtest/gtest.h>

#include "eval/ate.h"
#include "eval/improvement.h"
#include "eval/matched_trajectories.h"
#include "eval/motion_truth.h"
#include "slam/detect/sim_detector.h"
#include "slam/io/settings.h"
#include "slam/io/tum_sequence.h"
#include "slam/reject/rejection_filter.h"
#include "slam/system/system.h"
#include "tests/support/render_helpers.h"

namespace depot::test {
namespace {

struct Result {
  double ate = 0;
  eval::RejectionScore score;
  int lost = 0;
};

Result run(const std::string& dataset, slam::RejectionMode mode, bool threaded) {
  slam::TumSequence sequence(dataset);
  slam::SlamSettings settings = slam::load_settings(sequence.calibration_path());
  settings.threaded_mapping = threaded;
  slam::SimDetector detector(dataset);
  slam::AprioriClasses classes =
      slam::AprioriClasses::load(std::string(DEPOT_SOURCE_DIR) + "/scenes/apriori/depot.yaml");
  classes.check_against(detector.class_names(), "depot.yaml", "sim");
  slam::RejectionFilter filter(mode, classes, &detector);
  slam::System system(settings, mode == slam::RejectionMode::kOrb ? nullptr : &filter);
  eval::MotionTruth truth(dataset);
  Result r;
  cv::Mat bgr, depth;
  for (size_t i = 0; i < sequence.size(); ++i) {
    sequence.load(i, bgr, depth);
    const double t = sequence.entry(i).rgb_timestamp;
    auto tr = system.track(bgr, depth, t);
    r.lost += tr.state == slam::TrackingState::kLost;
    if (mode != slam::RejectionMode::kOrb)
      r.score.add(filter.last_keep(), truth.on_moving_object(t, filter.last_keypoints()));
  }
  system.finish();
  auto gt = read_tum_trajectory(dataset + "/groundtruth.txt");
  r.ate = eval::compute_ate(eval::match_trajectories(gt, system.trajectory(), {}, "gt", "est"))
              .statistics.rmse;
  return r;
}

TEST(RejectSystem, FullModeBeatsPlainOrbOnWalkingPeople) {
  std::string data = render_small({"depot_walking_xyz", 200, 640, false});
  Result orb = run(data, slam::RejectionMode::kOrb, true);
  Result full = run(data, slam::RejectionMode::kFull, false);
  Result yolo = run(data, slam::RejectionMode::kOrbYolo, false);
  const double rho = eval::improvement_percent(orb.ate, full.ate);
  std::printf(
      "walking_xyz 200 frames: ATE orb %.4f, orb+yolo %.4f, full %.4f m (improvement %.1f %%); "
      "full "
      "precision %.3f recall %.3f\n",
      orb.ate, yolo.ate, full.ate, rho, full.score.precision(), full.score.recall());
  EXPECT_LT(full.ate, 0.03);
  EXPECT_GT(rho, 80.0);
  EXPECT_EQ(full.lost, 0);
  // The rejected points are mostly on moving people (recall), even though box-level
  // rejection also throws away background inside the boxes (precision).
  EXPECT_GT(full.score.recall(), 0.8);
  EXPECT_GT(full.score.precision(), 0.25);
}

}  // namespace
}  // namespace depot::test
