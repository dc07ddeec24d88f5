#include "tools/harness/schedule/sweep_runner.h"

#include <cstdio>
#include <map>
#include <set>

#include "common/error.h"
#include "tools/harness/schedule/process_pool.h"
#include "tools/harness/schedule/slurm_submission.h"
#include "tools/harness/plan/sweep_folder.h"
#include "tools/harness/plan/sweep_job_state.h"
#include "tools/harness/schedule/sweep_progress.h"
#include "tools/harness/schedule/sweep_status.h"

namespace depot::harness {

std::vector<std::string> job_command(const std::string& program, const SweepLayout& layout,
                                     const SweepJob& job) {
  return {program, "sweep", "job", layout.root, job.id};
}

SweepRunResult run_sweep(const SweepPlan& plan, const SweepLayout& layout,
                         const SweepRunOptions& options, const std::atomic<bool>& stop) {
  SweepRunResult result;
  result.jobs = plan.jobs.size();
  SweepFolderLock lock(layout.root, "local");
  if (!options.assume_queue_empty) require_no_queued_tasks(layout);
  remove_leftovers(layout);
  const PendingWork work = find_pending_work(plan, layout);
  warn_corrupt_records(work);
  result.already_finished = work.already_finished;
  // A runner stopped between a dataset's last run and its clean-up left it behind.
  if (!plan.spec.keep_data)
    for (const auto& id : work.datasets_done) remove_dataset(layout, id);

  // Interleave: a dataset's render job, then its runs, so datasets are
  // consumed (and removed) early instead of all rendered up front.
  std::vector<ProcessJob> processes;
  std::vector<size_t> plan_index;
  std::map<std::string, size_t> runs_left;  // dataset id -> unfinished runs
  for (const PendingDataset& dataset : work.datasets) {
    const SweepJob& render = plan.jobs[dataset.render];
    std::vector<size_t> needs;
    if (dataset.needs_render) {
      processes.push_back(
          {job_command(options.program, layout, render), layout.log_file(render.id), {}});
      plan_index.push_back(dataset.render);
      needs.push_back(processes.size() - 1);
    }
    for (size_t r : dataset.runs) {
      processes.push_back({job_command(options.program, layout, plan.jobs[r]),
                           layout.log_file(plan.jobs[r].id), needs});
      plan_index.push_back(r);
    }
    runs_left[render.id] = dataset.runs.size();
  }

  SweepProgress progress(processes.size(), options.progress);
  if (options.progress)
    std::fprintf(stderr,
                 "sweep: %zu jobs in %s, %zu already finished, %zu to run on %d worker(s)\n",
                 result.jobs, layout.root.c_str(), result.already_finished, processes.size(),
                 options.workers);

  std::set<std::string> running;  // for `sweep status`, in the lock file
  auto on_finished = [&](size_t p, const JobOutcome& outcome) {
    const SweepJob& job = plan.jobs[plan_index[p]];
    if (running.erase(job.id)) lock.set_running(running);
    std::string line;
    if (stop.load() && outcome.state != JobState::kSucceeded) {
      // Stopped by the same Ctrl-C as the sweep: not a failure, keep its data.
      if (options.progress) std::fprintf(stderr, "sweep: %s interrupted\n", job.id.c_str());
      return;
    }
    if (outcome.state == JobState::kSucceeded) {
      try {
        line = describe_finished_job(job, layout);
      } catch (const Error& e) {
        line = job.id + ": " + e.what();
      }
    } else if (outcome.state == JobState::kBlocked) {
      line = job.id + ": skipped, its dataset failed to render";
    } else {
      line = job.id + ": FAILED (exit " + std::to_string(outcome.exit_code) + "), see " +
             layout.log_file(job.id);
      write_failure_record(layout, job.id,
                           {{"id", job.id},
                            {"exit_code", outcome.exit_code},
                            {"log", layout.log_file(job.id)},
                            {"log_tail", file_tail(layout.log_file(job.id), 8)}});
    }
    const bool dataset_used_up =
        job.kind == JobKind::kSlam ? --runs_left[job.dataset_id] == 0 : runs_left[job.id] == 0;
    if (dataset_used_up && !plan.spec.keep_data) remove_dataset(layout, job.dataset_id);
    progress.finished(line);
  };
  // A line as each job starts, so a long first job does not look like a hang.
  auto on_started = [&](size_t p) {
    const SweepJob& job = plan.jobs[plan_index[p]];
    remove_failure_record(layout, job.id);  // a new chance
    running.insert(job.id);
    lock.set_running(running);
    progress.started(job.id);
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
