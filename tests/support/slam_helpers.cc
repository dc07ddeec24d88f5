#include "tests/support/slam_helpers.h"

#include "common/tum_io.h"
#include "eval/ate.h"
#include "eval/matched_trajectories.h"
#include "tools/runner/slam_runner.h"

namespace depot::test {

SlamOutcome run_slam_mode(const std::string& dataset, slam::RejectionMode mode, bool threaded,
                          const slam::RejectionParams& params) {
  // The product's own run of one sequence (what `depot slam run` does), so
  // the tests exercise its wiring: the default `--detector sim` (the shipped,
  // calibrated error model) and the depot class table.
  runner::RunOptions options;
  options.input.dataset = dataset;
  options.rejection.mode = slam::rejection_mode_name(mode);
  options.input.sync = !threaded;
  options.quiet = true;
  options.rejection.params = params;
  const runner::RunSummary s = runner::run_sequence(options);
  SlamOutcome r;
  r.score = s.score;
  r.lost = s.lost;
  r.frames = s.frames;
  r.tracked = s.tracked;
  r.trajectory_size = s.trajectory.size();
  const auto gt = read_tum_trajectory(dataset + "/groundtruth.txt");
  r.ate_rmse = eval::compute_ate(eval::match_trajectories(gt, s.trajectory, {}, "gt", "est"))
                   .statistics.rmse;
  return r;
}

}  // namespace depot::test
