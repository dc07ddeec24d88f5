#pragma once
// The work of one sweep job, done in the calling process (`depot sweep job`
// runs exactly one, so each job is its own process with its own log):
//   render: the cell's scenario with its overrides and the job's seed to
//           data/<id>/, then data/<id>.json with the measured moving share;
//   slam:   one mode on that dataset to runs/<id>/ (trajectory.txt,
//           stats.csv, ate.svg, result.json), staged so it appears whole.
#include "tools/harness/run_record.h"
#include "tools/harness/sweep_plan.h"

namespace depot::harness {

// Loads every cell's scenario with its overrides and checks its detector and
// rejection settings, so a bad grid fails in one line before any job runs.
void check_sweep_inputs(const SweepPlan& plan);

DatasetRecord run_render_job(const SweepPlan& plan, const SweepLayout& layout, const SweepJob& job);

// A run whose tracking never starts is recorded with ok = false and its
// reason; other errors (missing dataset, interruption) throw.
RunRecord run_slam_job(const SweepPlan& plan, const SweepLayout& layout, const SweepJob& job);

}  // namespace depot::harness
