#include "tools/harness/schedule/slurm_scheduler.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <thread>

#include <nlohmann/json.hpp>

#include "common/error.h"
#include "tools/harness/plan/run_record.h"
#include "tools/harness/schedule/slurm_client.h"
#include "tools/harness/schedule/slurm_submission.h"
#include "tools/harness/plan/sweep_folder.h"
#include "tools/harness/plan/sweep_job_state.h"
#include "tools/harness/schedule/sweep_progress.h"
#include "tools/harness/schedule/sweep_status.h"

namespace fs = std::filesystem;

namespace depot::harness {
namespace {

// Array index i is the i-th dataset with runs left. The render array holds
// the datasets to render; SLAM array k (after_render) holds the k-th run of
// each of those, and a second one the k-th run of datasets already rendered,
// which wait for nothing.
SlurmSubmission plan_arrays(const SweepPlan& plan, const PendingWork& work) {
  SlurmSubmission s;
  SlurmArray render{"", JobKind::kRender, false, {}};
  std::map<std::pair<size_t, bool>, SlurmArray> runs;  // (k, after_render) -> array
  for (size_t d = 0; d < work.datasets.size(); ++d) {
    const PendingDataset& dataset = work.datasets[d];
    const int index = static_cast<int>(d);
    if (dataset.needs_render) render.tasks[index] = plan.jobs[dataset.render].id;
    for (size_t k = 0; k < dataset.runs.size(); ++k) {
      SlurmArray& array = runs[{k, dataset.needs_render}];
      array.kind = JobKind::kSlam;
      array.after_render = dataset.needs_render;
      array.tasks[index] = plan.jobs[dataset.runs[k]].id;
    }
  }
  if (!render.tasks.empty()) s.arrays.push_back(render);
  for (auto& [key, array] : runs) s.arrays.push_back(array);
  return s;
}

std::vector<std::string> common_sbatch_args(const SweepLayout& layout, const SlurmOptions& o) {
  std::vector<std::string> args = {
      "--job-name=depot-sweep:" + fs::path(layout.root).filename().string(),
      "--output=" + slurm_dir(layout) + "/out/%A_%a.out", "--chdir=" + layout.root};
  if (!o.partition.empty()) args.push_back("--partition=" + o.partition);
  if (!o.account.empty()) args.push_back("--account=" + o.account);
  if (!o.time_limit.empty()) args.push_back("--time=" + o.time_limit);
  if (!o.memory.empty()) args.push_back("--mem=" + o.memory);
  if (o.cpus_per_task > 0) args.push_back("--cpus-per-task=" + std::to_string(o.cpus_per_task));
  args.insert(args.end(), o.sbatch_args.begin(), o.sbatch_args.end());
  return args;
}

// The script and its arguments: attempts, task list, log folder, then the
// local pool's command for a job without its id (the script appends it).
std::vector<std::string> task_command(const SweepLayout& layout, size_t array,
                                      const SweepRunOptions& options, const SlurmOptions& slurm) {
  std::vector<std::string> command = {task_script_path(layout), std::to_string(slurm.retries + 1),
                                      task_list_path(layout, array),
                                      fs::path(layout.log_file("x")).parent_path().string()};
  std::vector<std::string> job = job_command(options.program, layout, SweepJob{});
  job.pop_back();  // the id
  command.insert(command.end(), job.begin(), job.end());
  return command;
}

std::vector<std::string> array_args(const SlurmSubmission& s, size_t k, const SweepLayout& layout,
                                    const SweepRunOptions& options, const SlurmOptions& slurm) {
  const SlurmArray& array = s.arrays[k];
  std::vector<std::string> args = common_sbatch_args(layout, slurm);
  args.push_back("--array=" + array_indices(array));
  if (array.after_render) {
    // Cancelled (not left pending forever) when its render failed.
    args.push_back("--dependency=aftercorr:" + s.arrays.front().job_id);
    args.push_back("--kill-on-invalid-dep=yes");
  }
  const std::vector<std::string> command = task_command(layout, k, options, slurm);
  args.insert(args.end(), command.begin(), command.end());
  return args;
}

void submit(SlurmSubmission& s, const SweepLayout& layout, const SweepRunOptions& options,
            const SlurmOptions& slurm) {
  // A bad option (time, account, memory, an extra argument) fails here, before anything is queued.
  std::vector<std::string> test = array_args(s, 0, layout, options, slurm);
  test.insert(test.begin(), "--test-only");
  sbatch(test);
  std::vector<std::string> submitted;
  try {
    for (size_t k = 0; k < s.arrays.size(); ++k) {
      s.arrays[k].job_id = sbatch(array_args(s, k, layout, options, slurm));
      submitted.push_back(s.arrays[k].job_id);
    }
  } catch (...) {
    scancel(submitted);  // all or nothing
    throw;
  }
}

struct TrackedTask {
  size_t job = 0;  // plan index
  bool running = false, ended = false;
};

// How a task that left the queue ended, from what it left behind.
std::string ending_line(const SweepPlan& plan, const SweepLayout& layout, const SweepJob& job,
                        const SlurmOptions& slurm, bool& failed, bool& blocked) {
  failed = blocked = false;
  if (job_finished(layout, job)) {
    try {
      return describe_finished_job(job, layout);
    } catch (const Error& e) {
      return job.id + ": " + e.what();
    }
  }
  const SweepJob& render = find_job(plan, job.dataset_id, layout.root);
  if (job.kind == JobKind::kSlam && !job_finished(layout, render)) {
    blocked = true;
    return job.id + ": skipped, its dataset failed to render";
  }
  failed = true;
  const std::string log = layout.log_file(job.id);
  write_failure_record(layout, job.id,
                       {{"id", job.id},
                        {"attempts", slurm.retries + 1},
                        {"log", log},
                        {"log_tail", file_tail(log, 8)}});
  // The console gets the last lines; the failure record keeps more.
  const std::string last = file_tail(log, 3);
  std::string indented;
  for (size_t a = 0; a < last.size();) {
    const size_t b = last.find('\n', a);
    indented += "\n    " + last.substr(a, b - a);
    a = b + 1;
  }
  return job.id + ": FAILED (ended without a record after at most " +
         std::to_string(slurm.retries + 1) + " attempt(s)), see " + log + indented;
}

void cancel_and_wait(const std::set<std::string>& ids) {
  scancel({ids.begin(), ids.end()});
  for (int i = 0; i < 120 && !queued_tasks(ids).empty(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(250));
}

}  // namespace

SlurmRunResult run_sweep_on_slurm(const SweepPlan& plan, const SweepLayout& given_layout,
                                  const SweepRunOptions& options, const SlurmOptions& slurm,
                                  const std::atomic<bool>& stop) {
  require_slurm_clients();
  if (!slurm.partition.empty()) require_partition(slurm.partition);
  // The tasks run elsewhere: every path they get is absolute.
  const SweepLayout layout{fs::absolute(given_layout.root).lexically_normal().string()};
  SlurmRunResult result;
  result.run.jobs = plan.jobs.size();
  const SweepFolderLock lock(layout.root, "slurm");
  if (!options.assume_queue_empty) require_no_queued_tasks(layout);
  remove_leftovers(layout);
  const PendingWork work = find_pending_work(plan, layout);
  warn_corrupt_records(work);
  result.run.already_finished = work.already_finished;
  if (!plan.spec.keep_data)
    for (const auto& id : work.datasets_done) remove_dataset(layout, id);

  SlurmSubmission submission = plan_arrays(plan, work);
  std::map<std::pair<std::string, int>, TrackedTask> tasks;  // (array job id, index)
  std::map<std::string, size_t> runs_left;                   // dataset id -> unfinished runs
  for (const PendingDataset& d : work.datasets) runs_left[plan.jobs[d.render].id] = d.runs.size();
  std::map<std::string, size_t> plan_index;
  for (size_t i = 0; i < plan.jobs.size(); ++i) plan_index[plan.jobs[i].id] = i;

  size_t to_run = 0;
  for (const auto& a : submission.arrays) to_run += a.tasks.size();
  if (to_run > 0) {
    write_task_files(layout, submission);
    submit(submission, layout, options, slurm);
    write_submission(layout, submission);
    // A job resubmitted gets a new chance: its old failure no longer stands.
    for (const auto& a : submission.arrays)
      for (const auto& [index, id] : a.tasks) {
        remove_failure_record(layout, id);
        tasks[{a.job_id, index}] = {plan_index.at(id)};
      }
  }
  std::set<std::string> ids;
  for (const auto& a : submission.arrays) {
    ids.insert(a.job_id);
    result.array_job_ids.push_back(a.job_id);
  }
  if (options.progress) {
    std::string list;
    for (const auto& id : result.array_job_ids) list += (list.empty() ? "" : ",") + id;
    std::fprintf(stderr,
                 "sweep: %zu jobs in %s, %zu already finished, %zu submitted to Slurm as %zu "
                 "array(s)%s\n",
                 result.run.jobs, layout.root.c_str(), result.run.already_finished, to_run,
                 submission.arrays.size(), list.empty() ? "" : (" (job " + list + ")").c_str());
  }
  if (slurm.detach && to_run > 0) {
    result.detached = true;
    return result;
  }

  SweepProgress progress(to_run, options.progress);
  size_t ended = 0;
  while (ended < tasks.size()) {
    if (stop.load()) {
      if (!slurm.detach) cancel_and_wait(ids);
      result.run.interrupted = true;
      break;
    }
    // The queue first, then the records: a task gone from the queue wrote
    // its record (if any) before it left, so it is seen below.
    std::map<std::pair<std::string, int>, QueuedTask> queued;
    size_t running = 0, pending = 0;
    for (const QueuedTask& q : queued_tasks(ids)) {
      queued[{q.array_job_id, q.index}] = q;
      (q.state == "PENDING" ? pending : running)++;
    }
    for (auto& [key, task] : tasks) {
      if (task.ended) continue;
      const SweepJob& job = plan.jobs[task.job];
      auto q = queued.find(key);
      if (q != queued.end()) {
        if (!task.running && q->second.state != "PENDING") {
          task.running = true;
          progress.started(job.id, ", " + std::to_string(running) + " running, " +
                                       std::to_string(pending) + " pending");
        }
        continue;
      }
      task.ended = true;
      ++ended;
      bool failed = false, blocked = false;
      const std::string line = ending_line(plan, layout, job, slurm, failed, blocked);
      result.run.succeeded += !failed && !blocked;
      result.run.failed += failed;
      result.run.blocked += blocked;
      const bool dataset_used_up =
          job.kind == JobKind::kSlam ? --runs_left[job.dataset_id] == 0 : runs_left[job.id] == 0;
      if (dataset_used_up && !plan.spec.keep_data) remove_dataset(layout, job.dataset_id);
      progress.finished(line);
    }
    if (ended == tasks.size()) break;
    for (double waited = 0; waited < slurm.poll_seconds && !stop.load(); waited += 0.1)
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return result;
}

}  // namespace depot::harness
