#include "tools/harness/sweep_runner.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>

#include "common/error.h"
#include "tools/harness/process_pool.h"
#include "tools/harness/run_record.h"

namespace fs = std::filesystem;

namespace depot::harness {
namespace {

// One runner per sweep folder: a second would run the same jobs and remove
// datasets and staged folders the first still uses.
class FolderLock {
 public:
  explicit FolderLock(const std::string& root) {
    const std::string path = (fs::path(root) / ".lock").string();
    fd_ = open(path.c_str(), O_CREAT | O_RDWR, 0644);
    if (fd_ < 0) fail(path, "cannot create the sweep's lock file");
    if (flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      close(fd_);
      fail(root, "another `depot sweep` is running in this folder");
    }
  }
  ~FolderLock() { close(fd_); }
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

 private:
  int fd_ = -1;
};

// Staged folders ("<name>.partial-<pid>") of jobs that were killed.
void remove_leftovers(const SweepLayout& layout) {
  for (const char* sub : {"data", "runs"}) {
    const fs::path dir = fs::path(layout.root) / sub;
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) continue;
    for (const auto& entry : fs::directory_iterator(dir, ec))
      if (entry.path().filename().string().find(".partial-") != std::string::npos)
        fs::remove_all(entry.path(), ec);
  }
}

// A dataset all of whose runs are done (its record stays).
void remove_dataset(const SweepLayout& layout, const std::string& id) {
  std::error_code ec;
  fs::remove_all(layout.dataset_dir(id), ec);
}

double tracked_percent(const RunRecord& r) {
  return r.frames ? 100.0 * r.tracked / r.frames : NAN;
}

std::string describe(const SweepJob& job, const SweepLayout& layout) {
  char buf[256];
  if (job.kind == JobKind::kRender) {
    const DatasetRecord d = read_dataset_record(layout.dataset_record(job.id));
    std::snprintf(buf, sizeof(buf), "rendered %s: %d frames, %.1f %% moving pixels", job.id.c_str(),
                  d.frames, 100 * d.moving_share_mean);
  } else {
    const RunRecord r = read_run_record(layout.run_record(job.id));
    if (!r.ok)
      std::snprintf(buf, sizeof(buf), "%s: no trajectory (%s)", job.id.c_str(), r.error.c_str());
    else if (std::isfinite(r.precision))
      std::snprintf(buf, sizeof(buf),
                    "%s: ATE %.4f m, precision %.2f (boundary static %.2f) recall %.2f, tracked "
                    "%.1f %%, lost %d",
                    job.id.c_str(), r.ate_rmse, r.precision_without_boundary, r.precision, r.recall,
                    tracked_percent(r), r.lost);
    else
      std::snprintf(buf, sizeof(buf), "%s: ATE %.4f m, tracked %.1f %%, lost %d", job.id.c_str(),
                    r.ate_rmse, tracked_percent(r), r.lost);
  }
  return buf;
}

}  // namespace

std::vector<std::string> job_command(const std::string& program, const SweepLayout& layout,
                                     const SweepJob& job) {
  return {program, "sweep", "job", layout.root, job.id};
}

SweepRunResult run_sweep(const SweepPlan& plan, const SweepLayout& layout,
                         const SweepRunOptions& options, const std::atomic<bool>& stop) {
  SweepRunResult result;
  result.jobs = plan.jobs.size();
  const FolderLock lock(layout.root);
  remove_leftovers(layout);

  // Which runs are left, and which datasets they need (re-rendered if a
  // finished dataset was already removed).
  std::map<std::string, std::vector<size_t>> pending_runs_of;  // dataset id -> slam jobs
  for (size_t i = 0; i < plan.jobs.size(); ++i) {
    const SweepJob& job = plan.jobs[i];
    if (job.kind != JobKind::kSlam) continue;
    if (job_finished(layout, job))
      ++result.already_finished;
    else
      pending_runs_of[job.dataset_id].push_back(i);
  }
  // Interleave: a dataset's render job, then its runs, so datasets are
  // consumed (and removed) early instead of all rendered up front.
  std::vector<ProcessJob> processes;
  std::vector<size_t> plan_index;
  for (size_t i = 0; i < plan.jobs.size(); ++i) {
    const SweepJob& job = plan.jobs[i];
    if (job.kind != JobKind::kRender) continue;
    auto it = pending_runs_of.find(job.id);
    const bool data_ready =
        job_finished(layout, job) && fs::is_directory(layout.dataset_dir(job.id));
    if (it == pending_runs_of.end()) {
      result.already_finished += job_finished(layout, job);
      // Every run of it is done: a runner stopped between its last run and
      // the clean-up left the dataset behind.
      if (!plan.spec.keep_data) remove_dataset(layout, job.id);
      continue;
    }
    std::vector<size_t> needs;
    if (data_ready) {
      ++result.already_finished;
    } else {
      processes.push_back({job_command(options.program, layout, job), layout.log_file(job.id), {}});
      plan_index.push_back(i);
      needs.push_back(processes.size() - 1);
    }
    for (size_t r : it->second) {
      processes.push_back({job_command(options.program, layout, plan.jobs[r]),
                           layout.log_file(plan.jobs[r].id), needs});
      plan_index.push_back(r);
    }
  }

  std::map<std::string, size_t> runs_left;  // dataset id -> unfinished runs
  for (const auto& [dataset, runs] : pending_runs_of) runs_left[dataset] = runs.size();
  const auto start = std::chrono::steady_clock::now();
  size_t done = 0;
  if (options.progress)
    std::fprintf(stderr,
                 "sweep: %zu jobs in %s, %zu already finished, %zu to run on %d worker(s)\n",
                 result.jobs, layout.root.c_str(), result.already_finished, processes.size(),
                 options.workers);

  auto on_finished = [&](size_t p, const JobOutcome& outcome) {
    const SweepJob& job = plan.jobs[plan_index[p]];
    ++done;
    std::string line;
    if (stop.load() && outcome.state != JobState::kSucceeded) {
      // Stopped by the same Ctrl-C as the sweep: not a failure, keep its data.
      if (options.progress) std::fprintf(stderr, "sweep: %s interrupted\n", job.id.c_str());
      return;
    }
    if (outcome.state == JobState::kSucceeded) {
      try {
        line = describe(job, layout);
      } catch (const Error& e) {
        line = job.id + ": " + e.what();
      }
    } else if (outcome.state == JobState::kBlocked) {
      line = job.id + ": skipped, its dataset failed to render";
    } else {
      line = job.id + ": FAILED (exit " + std::to_string(outcome.exit_code) + "), see " +
             layout.log_file(job.id);
    }
    if (job.kind == JobKind::kSlam && --runs_left[job.dataset_id] == 0 && !plan.spec.keep_data)
      remove_dataset(layout, job.dataset_id);
    if (options.progress) {
      const double elapsed =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const double eta = elapsed / done * (processes.size() - done);
      std::fprintf(stderr, "sweep: [%zu/%zu] %s  (%.0f s elapsed, about %.0f s left)\n", done,
                   processes.size(), line.c_str(), elapsed, eta);
    }
  };
  // A line as each job starts, so a long first job does not look like a hang.
  auto on_started = [&](size_t p) {
    if (!options.progress) return;
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stderr, "sweep: [%zu/%zu] started %s  (%.0f s elapsed)\n", done, processes.size(),
                 plan.jobs[plan_index[p]].id.c_str(), elapsed);
  };
  const PoolSummary pool =
      run_process_jobs(processes, options.workers, on_finished, stop, on_started);
  result.succeeded = pool.succeeded;
  result.failed = pool.failed;
  result.blocked = pool.blocked;
  result.interrupted = pool.interrupted;
  return result;
}

}  // namespace depot::harness
