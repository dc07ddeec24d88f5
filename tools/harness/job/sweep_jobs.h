#pragma once
// The work of one sweep job, done in the calling process (`depot sweep job`
// runs exactly one, so each job is its own process with its own log):
//   render: the cell's scenario with its overrides and the job's seed to
//           data/<id>/, then data/<id>.json with the measured moving share;
//   slam:   one mode on that dataset to runs/<id>/ (trajectory.txt,
//           states.txt, atlas.txt, stats.csv, ate.svg, result.json),
//           staged so it appears whole;
//           a system under test ("system:NAME", tools/system/) writes
//           system.log (its output) instead of stats.csv.
#include <string>
#include <vector>

#include "common/tum_io.h"
#include "eval/motion_truth.h"
#include "slam/track/tracking_state.h"
#include "tools/harness/plan/run_record.h"
#include "tools/harness/plan/sweep_plan.h"

namespace depot::harness {

// Loads every cell's scenario with its overrides and checks its detector and
// rejection settings, so a bad grid fails in one line before any job runs.
void check_sweep_inputs(const SweepPlan& plan);

DatasetRecord run_render_job(const SweepPlan& plan, const SweepLayout& layout, const SweepJob& job);

// ATE and RPE (1 s) of a run's trajectory against the ground truth into
// `r`, and the ATE plot to `plot_path`. A trajectory too short to align
// (under 3 poses) sets r.ok = false with the reason: the run lost the
// camera, which is an outcome of the sweep, not a failed job.
void add_accuracy(const std::vector<StampedPose>& truth, const std::vector<StampedPose>& trajectory,
                  const std::string& plot_path, RunRecord& r);

// The atlas's figures into `r` (after add_accuracy): frames with a pose in
// any map, the maps, and ATE over all of them with each map aligned on its
// own (eval/maps_ate.h). States that name no maps (another system's) give
// the trajectory's figures.
void add_atlas_accuracy(const std::vector<StampedPose>& truth,
                        const std::vector<StampedPose>& atlas,
                        const std::vector<slam::StampedFrameState>& states, RunRecord& r);

// A run's rejection figures from its score.
void add_rejection(const eval::RejectionScore& score, RunRecord& r);

// A run whose tracking never starts is recorded with ok = false and its
// reason; other errors (missing dataset, interruption) throw.
RunRecord run_slam_job(const SweepPlan& plan, const SweepLayout& layout, const SweepJob& job);

}  // namespace depot::harness
