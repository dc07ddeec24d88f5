#include "tests/support/slam_helpers.h"

#include "common/tum_io.h"
#include "eval/ate.h"
#include "eval/keypoint_score.h"
#include "eval/matched_trajectories.h"
#include "slam/detect/sim_detector.h"
#include "slam/io/settings.h"
#include "slam/io/tum_sequence.h"
#include "slam/system/system.h"
#include "tools/runner/slam_runner.h"

namespace depot::test {

SlamOutcome run_slam_mode(const std::string& dataset, slam::RejectionMode mode, bool threaded,
                          const slam::RejectionParams& params) {
  slam::TumSequence sequence(dataset);
  slam::SlamSettings settings = slam::load_settings(sequence.calibration_path());
  settings.threaded_mapping = threaded;
  sequence.set_depth_factor(settings.camera.depth_factor);
  // The default of `--detector sim`: the shipped, calibrated error model.
  slam::SimDetector detector(dataset, runner::sim_detector_config(runner::RunOptions{}));
  slam::AprioriClasses classes =
      slam::AprioriClasses::load(std::string(DEPOT_SOURCE_DIR) + "/scenes/apriori/depot.yaml");
  classes.check_against(detector.class_names(), "depot.yaml", "sim");
  slam::RejectionFilter filter(mode, classes, &detector, params);
  slam::System system(settings, mode == slam::RejectionMode::kOrb ? nullptr : &filter);
  eval::MotionTruth truth(dataset);
  SlamOutcome r;
  cv::Mat bgr, depth;
  for (size_t i = 0; i < sequence.size(); ++i) {
    sequence.load(i, bgr, depth);
    const double t = sequence.entry(i).rgb_timestamp;
    auto tr = system.track(bgr, depth, t);
    r.lost += tr.state == slam::TrackingState::kLost;
    if (mode != slam::RejectionMode::kOrb) {
      r.score.add(eval::score_frame(truth, t, filter.last_keypoints(), filter.last_keep(),
                                    settings.orb.scale_factor));
    }
  }
  system.finish();
  const auto estimate = system.trajectory();
  r.trajectory_size = estimate.size();
  const auto states = system.frame_states();
  r.frames = states.size();
  for (const auto& s : states) r.tracked += slam::is_tracked(s.state);
  auto gt = read_tum_trajectory(dataset + "/groundtruth.txt");
  r.ate_rmse =
      eval::compute_ate(eval::match_trajectories(gt, estimate, {}, "gt", "est")).statistics.rmse;
  return r;
}

}  // namespace depot::test
