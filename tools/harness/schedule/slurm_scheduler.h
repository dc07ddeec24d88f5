#pragma once
// Runs a sweep's unfinished jobs on a Slurm cluster instead of local workers:
// the render jobs as one job array, the SLAM jobs as arrays whose task i
// starts only after render task i succeeded (--dependency=aftercorr), each
// task running `depot sweep job OUT ID` as the local pool does (retried up to
// `retries` times). Then it follows the queue (squeue) and the records until
// the last job ends, with the local pool's progress lines; Ctrl-C cancels
// the arrays (scancel) unless detached. Assumes a shared filesystem: the
// sweep folder and the depot program are visible at the same paths on every
// node.
#include <atomic>
#include <string>
#include <vector>

#include "tools/harness/plan/sweep_plan.h"
#include "tools/harness/schedule/sweep_runner.h"

namespace depot::harness {

struct SlurmOptions {
  std::string partition, account, time_limit, memory;  // empty: the cluster's default
  int cpus_per_task = 0;                               // 0: the cluster's default
  std::vector<std::string> sbatch_args;                // passed to every sbatch as given
  int retries = 2;      // further attempts of a failed job inside its task
  bool detach = false;  // submit and return
  double poll_seconds = 2;
};

struct SlurmRunResult {
  SweepRunResult run;
  bool detached = false;
  std::vector<std::string> array_job_ids;
};

// Throws Error, with nothing submitted, when the Slurm clients are missing,
// the partition is unknown, a task of an earlier submission of this folder
// is still queued or running (sweep_status.h: require_no_queued_tasks, as
// the local pool asks too), or sbatch rejects a submission (then the arrays
// submitted before it are cancelled).
SlurmRunResult run_sweep_on_slurm(const SweepPlan& plan, const SweepLayout& layout,
                                  const SweepRunOptions& options, const SlurmOptions& slurm,
                                  const std::atomic<bool>& stop);

}  // namespace depot::harness
