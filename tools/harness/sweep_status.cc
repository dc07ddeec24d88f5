#include "tools/harness/sweep_status.h"

#include <filesystem>
#include <map>
#include <set>

#include "common/error.h"
#include "tools/harness/command_output.h"
#include "tools/harness/slurm_client.h"
#include "tools/harness/slurm_submission.h"

namespace fs = std::filesystem;

namespace depot::harness {

SweepStatus read_sweep_status(const SweepPlan& plan, const SweepLayout& layout) {
  SweepStatus status;
  status.jobs = plan.jobs.size();
  std::map<std::string, std::string> queue_state;  // sweep job id -> Slurm state
  const auto submission = read_submission(layout);
  if (submission && find_on_path("squeue")) {
    std::set<std::string> ids;
    std::map<std::pair<std::string, int>, std::string> job_of;
    for (const auto& a : submission->arrays) {
      ids.insert(a.job_id);
      for (const auto& [index, id] : a.tasks) job_of[{a.job_id, index}] = id;
    }
    try {
      for (const QueuedTask& q : queued_tasks(ids)) {
        auto it = job_of.find({q.array_job_id, q.index});
        if (it != job_of.end()) queue_state[it->second] = q.state;
      }
      status.on_slurm = true;
    } catch (const Error& e) {
      status.queue_error = e.what();  // the records still tell what is done
    }
  }
  for (const SweepJob& job : plan.jobs) {
    auto q = queue_state.find(job.id);
    if (job_finished(layout, job)) {
      ++status.done;
    } else if (q != queue_state.end()) {
      (q->second == "PENDING" ? status.pending : status.running)++;
    } else if (fs::exists(failure_record_path(layout, job.id))) {
      ++status.failed;
      status.failed_jobs.push_back(job.id);
    } else {
      ++status.not_queued;
    }
  }
  return status;
}

}  // namespace depot::harness
