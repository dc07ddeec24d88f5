#pragma once
// Where a sweep stands, from its records (sweep_job_state.h), the Slurm
// queue when its jobs were submitted there, and the local runner working on
// it, if any: for `depot sweep status OUT`, while a sweep runs (locally or
// on Slurm, detached or not) or after it stopped.
#include <string>
#include <vector>

#include "tools/harness/plan/sweep_plan.h"

namespace depot::harness {

struct SweepStatus {
  size_t jobs = 0;
  size_t done = 0;                  // a record that reads back
  size_t without_trajectory = 0;    // of them, SLAM runs that kept no trajectory
  size_t running = 0, pending = 0;  // in the Slurm queue, or the local runner's pool
  size_t failed = 0;                // no record; its process failed (every attempt)
  size_t corrupt = 0;               // a record that does not read back
  size_t not_started = 0;           // none of the above: resume runs them
  std::vector<std::string> failed_jobs;
  std::vector<std::string> corrupt_records;          // "<path>: <problem>"
  std::vector<std::string> runs_without_trajectory;  // "<id>: <why>"
  bool on_slurm = false;    // submitted to Slurm and the queue could be read
  std::string queue_error;  // submitted to Slurm but squeue failed or is missing
  long local_runner = 0;    // pid of a local `depot sweep` running the jobs, or 0
};

SweepStatus read_sweep_status(const SweepPlan& plan, const SweepLayout& layout);

// Throws Error naming the folder when it was submitted to Slurm
// (OUT/slurm/submission.json) and any of those tasks is still queued or
// running, or the queue cannot be read (no squeue on PATH, or it fails):
// running the jobs here then could run each twice.
void require_no_queued_tasks(const SweepLayout& layout);

}  // namespace depot::harness
