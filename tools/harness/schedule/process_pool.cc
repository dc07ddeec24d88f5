#include "tools/harness/schedule/process_pool.h"

#include <signal.h>
#include <sys/wait.h>

#include <chrono>
#include <map>
#include <thread>

#include "common/child_process.h"
#include "common/error.h"

namespace depot::harness {
namespace {

pid_t spawn(const ProcessJob& job) {
  if (job.argv.empty()) fail("process pool", "job without a program");
  ChildSpec child;
  child.argv = job.argv;
  child.log_path = job.log_path;
  return start_child(child);
}

}  // namespace

namespace {

// Asks the children to stop (they clean up their staged output) and waits
// for them; forces after 20 s.
void stop_children(std::map<pid_t, size_t>& running) {
  for (const auto& [pid, i] : running) kill(pid, SIGTERM);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (!running.empty()) {
    int status = 0;
    const pid_t pid = waitpid(-1, &status, WNOHANG);
    if (pid > 0) {
      running.erase(pid);
      continue;
    }
    if (pid < 0) break;  // no children left
    if (std::chrono::steady_clock::now() > deadline)
      for (const auto& [p, i] : running) kill(p, SIGKILL);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  running.clear();
}

}  // namespace

PoolSummary run_process_jobs(const std::vector<ProcessJob>& jobs, int workers,
                             const JobFinished& on_finished, const std::atomic<bool>& stop,
                             const JobStarted& on_started) {
  if (workers < 1) fail("process pool", "needs at least one worker");
  std::vector<JobOutcome> outcome(jobs.size());
  std::map<pid_t, size_t> running;
  std::map<pid_t, std::chrono::steady_clock::time_point> started;
  PoolSummary summary;

  auto finish = [&](size_t i, JobState state, int code, double seconds) {
    outcome[i] = {state, code, seconds};
    (state == JobState::kSucceeded ? summary.succeeded
     : state == JobState::kFailed  ? summary.failed
                                   : summary.blocked)++;
    if (on_finished) on_finished(i, outcome[i]);
  };

  try {
    while (true) {
      if (stop.load()) {
        summary.interrupted = true;
        break;
      }
      // Start what can start, in list order.
      for (size_t i = 0; i < jobs.size() && static_cast<int>(running.size()) < workers; ++i) {
        if (outcome[i].state != JobState::kPending) continue;
        bool ready = true, blocked = false;
        for (size_t need : jobs[i].needs) {
          const JobState s = outcome.at(need).state;
          if (s == JobState::kFailed || s == JobState::kBlocked) blocked = true;
          if (s != JobState::kSucceeded) ready = false;
        }
        if (blocked) {
          finish(i, JobState::kBlocked, 0, 0);
          continue;
        }
        if (!ready) continue;
        const pid_t pid = spawn(jobs[i]);
        outcome[i].state = JobState::kRunning;
        running[pid] = i;
        started[pid] = std::chrono::steady_clock::now();
        if (on_started) on_started(i);
      }
      if (running.empty()) {
        // Anything still pending waits on a blocked need: mark and finish.
        bool changed = false;
        for (size_t i = 0; i < jobs.size(); ++i)
          if (outcome[i].state == JobState::kPending) {
            for (size_t need : jobs[i].needs)
              if (outcome[need].state == JobState::kFailed ||
                  outcome[need].state == JobState::kBlocked) {
                finish(i, JobState::kBlocked, 0, 0);
                changed = true;
                break;
              }
          }
        if (!changed) break;
        continue;
      }
      int status = 0;
      const pid_t pid = waitpid(-1, &status, WNOHANG);
      if (pid > 0 && running.count(pid)) {
        const size_t i = running[pid];
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - started[pid]).count();
        running.erase(pid);
        const int code = exit_code_of(status);
        finish(i, code == 0 ? JobState::kSucceeded : JobState::kFailed, code, seconds);
        continue;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  } catch (...) {
    // A job could not start or a callback failed: leave no child behind.
    stop_children(running);
    throw;
  }

  stop_children(running);  // only when interrupted are any still running
  for (const auto& o : outcome) summary.not_started += o.state == JobState::kPending;
  return summary;
}

}  // namespace depot::harness
