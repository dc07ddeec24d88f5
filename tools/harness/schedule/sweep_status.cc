#include "tools/harness/schedule/sweep_status.h"

#include <filesystem>
#include <map>
#include <optional>
#include <set>

#include "common/error.h"
#include "tools/harness/schedule/command_output.h"
#include "tools/harness/schedule/slurm_client.h"
#include "tools/harness/schedule/slurm_submission.h"
#include "tools/harness/plan/sweep_folder.h"
#include "tools/harness/plan/sweep_job_state.h"

namespace fs = std::filesystem;

namespace depot::harness {
namespace {

std::set<std::string> array_ids(const SlurmSubmission& submission) {
  std::set<std::string> ids;
  for (const auto& a : submission.arrays) ids.insert(a.job_id);
  return ids;
}

std::string joined(const std::set<std::string>& ids, const std::string& separator) {
  std::string text;
  for (const auto& id : ids) text += (text.empty() ? "" : separator) + id;
  return text;
}

}  // namespace

void require_no_queued_tasks(const SweepLayout& layout) {
  const auto submission = read_submission(layout);
  if (!submission) return;
  const std::set<std::string> ids = array_ids(*submission);
  const std::string file = slurm_dir(layout) + "/submission.json";
  const std::string escape = "; add --assume-queue-empty only if you know its tasks have ended";
  if (!find_on_path("squeue"))
    fail(layout.root, "was submitted to Slurm (" + file +
                          ") but squeue is not on PATH to see whether its tasks still run, so "
                          "nothing was run; resume it where Slurm's commands are" +
                          escape);
  std::vector<QueuedTask> queued;
  try {
    queued = queued_tasks(ids);
  } catch (const Error& e) {
    fail(layout.root, "was submitted to Slurm but its queue cannot be read (" +
                          std::string(e.what()) + "), so nothing was run" + escape);
  }
  if (queued.empty()) return;
  fail(layout.root, std::to_string(queued.size()) + " task(s) of its Slurm submission (job " +
                        joined(ids, ",") +
                        ") are still queued or running, so nothing was run; follow them with "
                        "`depot sweep status " +
                        layout.root + "` or cancel them with `scancel " + joined(ids, " ") + "`");
}

SweepStatus read_sweep_status(const SweepPlan& plan, const SweepLayout& layout) {
  SweepStatus status;
  status.jobs = plan.jobs.size();
  const std::optional<ActiveRunner> runner = active_runner(layout.root);
  const bool local = runner && runner->scheduler == "local";
  if (local) status.local_runner = runner->pid;
  std::map<std::string, std::string> queue_state;  // sweep job id -> Slurm state
  const auto submission = read_submission(layout);
  if (submission && !local) {
    std::map<std::pair<std::string, int>, std::string> job_of;
    for (const auto& a : submission->arrays)
      for (const auto& [index, id] : a.tasks) job_of[{a.job_id, index}] = id;
    try {
      if (!find_on_path("squeue")) fail("squeue", "not found on PATH");
      for (const QueuedTask& q : queued_tasks(array_ids(*submission))) {
        auto it = job_of.find({q.array_job_id, q.index});
        if (it != job_of.end()) queue_state[it->second] = q.state;
      }
      status.on_slurm = true;
    } catch (const Error& e) {
      status.queue_error = e.what();  // the records still tell what is done
    }
  }
  for (const SweepJob& job : plan.jobs) {
    const JobRecordState s = job_record_state(layout, job);
    auto q = queue_state.find(job.id);
    if (s.state == RecordState::kDone) {
      ++status.done;
      if (s.without_trajectory()) {
        ++status.without_trajectory;
        status.runs_without_trajectory.push_back(job.id + ": " + s.run->error);
      }
    } else if (q != queue_state.end()) {
      (q->second == "PENDING" ? status.pending : status.running)++;
    } else if (local && runner->running.count(job.id)) {
      ++status.running;
    } else if (s.state == RecordState::kFailed) {
      ++status.failed;
      status.failed_jobs.push_back(job.id);
    } else if (s.state == RecordState::kCorrupt) {
      ++status.corrupt;
      status.corrupt_records.push_back(s.problem);
    } else if (local) {
      ++status.pending;  // the local runner's pool starts it in turn
    } else {
      ++status.not_started;
    }
  }
  return status;
}

}  // namespace depot::harness
