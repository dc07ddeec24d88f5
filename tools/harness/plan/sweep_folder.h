#pragma once
// Housekeeping of a sweep folder shared by every way of running its jobs
// (the local process pool, a Slurm cluster): one runner at a time, leftovers
// of killed jobs, datasets no run needs any more, and which jobs are left.
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "tools/harness/plan/sweep_plan.h"

namespace depot::harness {

// One runner per sweep folder: a second would run the same jobs and remove
// datasets and staged folders the first still uses. Throws Error when held.
// The lock file (OUT/.lock) also says who holds it, for `sweep status`:
// "<scheduler> <pid>" and, for the local pool, the ids of its running jobs.
class SweepFolderLock {
 public:
  SweepFolderLock(const std::string& root, const std::string& scheduler);
  ~SweepFolderLock();
  SweepFolderLock(const SweepFolderLock&) = delete;
  SweepFolderLock& operator=(const SweepFolderLock&) = delete;

  // The jobs the local pool runs now.
  void set_running(const std::set<std::string>& job_ids);

 private:
  void write_owner(const std::set<std::string>& running);
  int fd_ = -1;
  std::string scheduler_;
};

// The runner holding a sweep folder's lock, if any.
struct ActiveRunner {
  std::string scheduler;  // "local" or "slurm"
  long pid = 0;
  std::set<std::string> running;  // local: the jobs its pool runs now
};
std::optional<ActiveRunner> active_runner(const std::string& root);

// Removes staged folders ("<name>.partial-<pid>") of jobs that were killed.
void remove_leftovers(const SweepLayout& layout);

// Removes a dataset all of whose runs are done (its record stays).
void remove_dataset(const SweepLayout& layout, const std::string& id);

// The unfinished work on one dataset.
struct PendingDataset {
  size_t render = 0;          // plan index of its render job
  bool needs_render = false;  // no record, or the data was already removed
  std::vector<size_t> runs;   // plan indices of its unfinished SLAM jobs
};

// A job whose record is corrupt: it runs again and its new record replaces the bad one.
struct CorruptRecord {
  std::string job_id;
  std::string problem;  // "<record path>: <what is wrong>"
};

struct PendingWork {
  size_t already_finished = 0;             // jobs with a record that need nothing more
  std::vector<PendingDataset> datasets;    // in plan order, only those with runs left
  std::vector<std::string> datasets_done;  // every run done: removable unless keep_data
  std::vector<CorruptRecord> corrupt;      // among the jobs left
};

// Which jobs are left (sweep_job_state.h: every job not done). A dataset
// whose runs are all done needs no render even if it was removed; one with
// runs left is rendered again if its data is gone.
PendingWork find_pending_work(const SweepPlan& plan, const SweepLayout& layout);

// "depot: warning: <problem>; job <id> runs again and its new record
// replaces this one" on stderr for each corrupt record (also with -q: a
// file of ours is about to be replaced).
void warn_corrupt_records(const PendingWork& work);

}  // namespace depot::harness
