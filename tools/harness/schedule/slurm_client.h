#pragma once
// The Slurm commands the sweep scheduler uses, each run with argv (no shell)
// through the client programs on PATH, as a user would: sbatch to submit,
// squeue for what is queued or running, scancel, sinfo for partitions.
// Errors are one line: the command and the first line it printed.
#include <set>
#include <string>
#include <vector>

namespace depot::harness {

// Throws Error naming the first of sbatch, squeue, scancel, sinfo missing on PATH.
void require_slurm_clients();

// Throws Error when `partition` is not one of the cluster's partitions.
void require_partition(const std::string& partition);

// `sbatch --parsable ARGS...` (add --test-only to check without submitting);
// returns the job id. Throws Error with sbatch's message when rejected.
std::string sbatch(const std::vector<std::string>& args);

// One array task (or plain job) still known to the queue.
struct QueuedTask {
  std::string array_job_id;  // the id sbatch returned
  int index = -1;            // array task index (-1: not an array)
  std::string state;         // PENDING, RUNNING, COMPLETING, ...
  std::string reason;        // why pending: None, Dependency, Priority, ...
};

// The user's tasks in the queue that belong to `array_job_ids`, one per array
// task (pending ranges expanded). Throws Error when squeue fails.
std::vector<QueuedTask> queued_tasks(const std::set<std::string>& array_job_ids);

// Cancels jobs (whole arrays or "<id>_<index>" tasks); errors are ignored,
// the jobs may have ended meanwhile.
void scancel(const std::vector<std::string>& job_ids);

}  // namespace depot::harness
