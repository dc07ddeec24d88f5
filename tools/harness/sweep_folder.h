#pragma once
// Housekeeping of a sweep folder shared by every way of running its jobs
// (the local process pool, a Slurm cluster): one runner at a time, leftovers
// of killed jobs, datasets no run needs any more, and which jobs are left.
#include <string>
#include <vector>

#include "tools/harness/sweep_plan.h"

namespace depot::harness {

// One runner per sweep folder: a second would run the same jobs and remove
// datasets and staged folders the first still uses. Throws Error when held.
class SweepFolderLock {
 public:
  explicit SweepFolderLock(const std::string& root);
  ~SweepFolderLock();
  SweepFolderLock(const SweepFolderLock&) = delete;
  SweepFolderLock& operator=(const SweepFolderLock&) = delete;

 private:
  int fd_ = -1;
};

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

struct PendingWork {
  size_t already_finished = 0;             // jobs with a record that need nothing more
  std::vector<PendingDataset> datasets;    // in plan order, only those with runs left
  std::vector<std::string> datasets_done;  // every run done: removable unless keep_data
};

// Which jobs are left. A dataset whose runs are all done needs no render even
// if it was removed; one with runs left is rendered again if its data is gone.
PendingWork find_pending_work(const SweepPlan& plan, const SweepLayout& layout);

}  // namespace depot::harness
