#pragma once
// The finished runs of a sweep gathered per cell and mode: mean and standard
// deviation over seeds of each figure (population std, as numpy and evo).
#include <map>
#include <string>
#include <vector>

#include "tools/harness/plan/run_record.h"
#include "tools/harness/plan/sweep_plan.h"

namespace depot::harness {

struct MeanStd {
  double mean = NAN;
  double std = NAN;
  int count = 0;  // finite values averaged
};

// NaN values are skipped; no finite value gives NaN, NaN.
MeanStd mean_std(const std::vector<double>& values);

struct CellModeSummary {
  size_t cell = 0;
  std::string mode;
  int runs = 0;                           // records found (sweep_job_state.h: done)
  int without_trajectory = 0;             // of them, runs that kept no trajectory
  int failed_jobs = 0;                    // no record: the job's process failed
  int corrupt = 0;                        // a record that does not read back
  int lost = 0;                           // lost frames over all runs
  MeanStd ate_rmse, ate_std;              // m
  MeanStd rpe_trans_rmse, rpe_trans_std;  // m
  MeanStd rpe_rot_rmse, rpe_rot_std;      // deg
  MeanStd precision, recall;              // boundary points counted as static
  MeanStd precision_without_boundary;     // boundary points left out
  MeanStd precision_with_depth;           // over keypoints with depth, boundary left out
  MeanStd recall_with_depth;              // over keypoints with depth
  MeanStd tracked_share;                  // frames in trajectory / frames
  MeanStd posed_share;                    // frames with a pose in any atlas map / frames
  MeanStd maps;                           // atlas maps holding frames
  MeanStd ate_all_maps_rmse;              // m, every map aligned on its own (eval/maps_ate.h)
  MeanStd moving_share;                   // pixels on moving objects
  std::map<int, RunRecord> runs_by_seed;
};

// The per-seed difference ours - baseline on one figure, over the seeds
// where both are finite: its mean ± std (population, like every spread in
// the tables) and the paired t statistic mean / (s / sqrt(n)) with the
// sample std s. |t| under about 2 means the seeds show no difference; NaN
// with fewer than two pairs or no spread.
struct PairedDifference {
  MeanStd difference;
  double t = NAN;
};
PairedDifference paired_difference(const CellModeSummary& baseline, const CellModeSummary& ours,
                                   double RunRecord::*figure);

// Eq. 9 of `ours` against `baseline` on one figure, from its means over the
// seeds where both have a finite value (a failed run of one mode must not
// compare different seeds). NaN when no seed pairs up.
double paired_improvement(const CellModeSummary& baseline, const CellModeSummary& ours,
                          double RunRecord::*figure);

struct SweepSummary {
  std::vector<CellModeSummary> entries;  // cell-major, modes in spec order
  std::vector<RunRecord> runs;           // every record found, in plan order
  size_t expected_runs = 0;
  size_t failed_jobs = 0;            // SLAM jobs whose process failed (no record)
  std::vector<std::string> corrupt;  // "<record path>: <problem>", left out
  // nullptr when the mode is not part of the sweep.
  const CellModeSummary* find(size_t cell, const std::string& mode) const;
};

// Reads every run record of the plan that reads back (missing ones are
// simply not counted, so a partial sweep can be reported); failed jobs and
// corrupt records (sweep_job_state.h) are counted and left out.
SweepSummary summarize_sweep(const SweepPlan& plan, const SweepLayout& layout);

// The same from records already in memory (for tests and tools).
SweepSummary summarize_records(const SweepPlan& plan, const std::vector<RunRecord>& records);

}  // namespace depot::harness
