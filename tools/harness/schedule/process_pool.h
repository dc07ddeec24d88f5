#pragma once
// Runs a list of commands as child processes, at most `workers` at a time,
// each with its output in its own log file. A job starts once the jobs it
// needs have succeeded (in list order otherwise); a job whose need failed is
// blocked. When `stop` becomes true (Ctrl-C, SIGTERM) the running children
// get SIGTERM and the pool returns once they have exited.
#include <atomic>
#include <functional>
#include <string>
#include <vector>

namespace depot::harness {

struct ProcessJob {
  std::vector<std::string> argv;  // argv[0] is the program's path
  std::string log_path;           // stdout and stderr, truncated at start
  std::vector<size_t> needs;      // indices of jobs that must succeed first
};

enum class JobState { kPending, kRunning, kSucceeded, kFailed, kBlocked };

struct JobOutcome {
  JobState state = JobState::kPending;
  int exit_code = 0;  // or 128 + signal number
  double seconds = 0;
};

struct PoolSummary {
  size_t succeeded = 0, failed = 0, blocked = 0, not_started = 0;
  bool interrupted = false;
};

using JobFinished = std::function<void(size_t index, const JobOutcome& outcome)>;
using JobStarted = std::function<void(size_t index)>;

// Throws Error when a program cannot be started or a log cannot be opened.
// `on_started` (optional) is called as each job's process starts.
PoolSummary run_process_jobs(const std::vector<ProcessJob>& jobs, int workers,
                             const JobFinished& on_finished, const std::atomic<bool>& stop,
                             const JobStarted& on_started = nullptr);

}  // namespace depot::harness
