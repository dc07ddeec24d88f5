#pragma once
// Runs a sweep's unfinished jobs, each as its own `depot sweep job` process,
// on a number of local workers; prints one progress line per finished job
// and removes a dataset once all its runs are done (unless keep_data). A
// killed sweep resumes here: finished jobs (those with a record) are
// skipped, jobs with a corrupt record run again, and leftovers of killed
// jobs are removed. A folder once submitted to Slurm is refused while any
// of its tasks is still queued or running (they would run the same jobs).
#include <atomic>
#include <string>

#include "tools/harness/plan/sweep_plan.h"

namespace depot::harness {

struct SweepRunOptions {
  std::string program;  // the depot executable
  int workers = 1;
  bool progress = true;
  // Skip the look at the Slurm queue of a folder submitted there (for when
  // squeue cannot answer and its tasks are known to have ended).
  bool assume_queue_empty = false;
};

struct SweepRunResult {
  size_t jobs = 0;              // in the plan
  size_t already_finished = 0;  // skipped
  size_t succeeded = 0, failed = 0, blocked = 0;
  bool interrupted = false;
};

SweepRunResult run_sweep(const SweepPlan& plan, const SweepLayout& layout,
                         const SweepRunOptions& options, const std::atomic<bool>& stop);

// The command that runs one job: `<program> sweep job <root> <id>`.
std::vector<std::string> job_command(const std::string& program, const SweepLayout& layout,
                                     const SweepJob& job);

}  // namespace depot::harness
