#pragma once
// Where a sweep stands, from its records and, when its jobs were submitted
// to Slurm, the queue: for `depot sweep status OUT`, while a detached sweep
// runs or after any sweep stopped.
#include <string>
#include <vector>

#include "tools/harness/sweep_plan.h"

namespace depot::harness {

struct SweepStatus {
  size_t jobs = 0;
  size_t done = 0;                  // a record exists
  size_t running = 0, pending = 0;  // in the Slurm queue
  size_t failed = 0;                // failed every attempt (a failure record, no result)
  size_t not_queued = 0;            // none of the above: resume runs them
  std::vector<std::string> failed_jobs;
  bool on_slurm = false;    // submitted to Slurm and the queue could be read
  std::string queue_error;  // submitted to Slurm but squeue failed
};

SweepStatus read_sweep_status(const SweepPlan& plan, const SweepLayout& layout);

}  // namespace depot::harness
