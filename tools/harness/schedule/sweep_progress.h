#pragma once
// The progress lines of a running sweep on stderr, the same whichever
// scheduler runs its jobs: one as a job starts, one as it finishes with what
// its record says, with elapsed time and an estimate of the time left.
#include <chrono>
#include <string>

#include "tools/harness/plan/sweep_plan.h"

namespace depot::harness {

// "rendered <id>: ..." or "<id>: ATE ..." from a finished job's record.
std::string describe_finished_job(const SweepJob& job, const SweepLayout& layout);

class SweepProgress {
 public:
  SweepProgress(size_t total, bool enabled);
  // "sweep: [done/total] started <id>  (X s elapsed<extra>)"
  void started(const std::string& job_id, const std::string& extra = "") const;
  // Counts one more finished job: "sweep: [done/total] <line>  (X s elapsed, about Y s left)"
  void finished(const std::string& line);
  size_t done() const { return done_; }

 private:
  double elapsed() const;
  size_t total_;
  bool enabled_;
  size_t done_ = 0;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace depot::harness
