#include "tools/harness/sweep_folder.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <filesystem>
#include <map>

#include "common/error.h"

namespace fs = std::filesystem;

namespace depot::harness {

SweepFolderLock::SweepFolderLock(const std::string& root) {
  const std::string path = (fs::path(root) / ".lock").string();
  fd_ = open(path.c_str(), O_CREAT | O_RDWR, 0644);
  if (fd_ < 0) fail(path, "cannot create the sweep's lock file");
  if (flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    close(fd_);
    fail(root, "another `depot sweep` is running in this folder");
  }
}

SweepFolderLock::~SweepFolderLock() {
  close(fd_);
}

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

void remove_dataset(const SweepLayout& layout, const std::string& id) {
  std::error_code ec;
  fs::remove_all(layout.dataset_dir(id), ec);
}

PendingWork find_pending_work(const SweepPlan& plan, const SweepLayout& layout) {
  PendingWork work;
  std::map<std::string, std::vector<size_t>> pending_runs_of;  // dataset id -> slam jobs
  for (size_t i = 0; i < plan.jobs.size(); ++i) {
    const SweepJob& job = plan.jobs[i];
    if (job.kind != JobKind::kSlam) continue;
    if (job_finished(layout, job))
      ++work.already_finished;
    else
      pending_runs_of[job.dataset_id].push_back(i);
  }
  for (size_t i = 0; i < plan.jobs.size(); ++i) {
    const SweepJob& job = plan.jobs[i];
    if (job.kind != JobKind::kRender) continue;
    auto it = pending_runs_of.find(job.id);
    if (it == pending_runs_of.end()) {
      work.already_finished += job_finished(layout, job);
      work.datasets_done.push_back(job.id);
      continue;
    }
    const bool data_ready =
        job_finished(layout, job) && fs::is_directory(layout.dataset_dir(job.id));
    work.already_finished += data_ready;
    work.datasets.push_back({i, !data_ready, it->second});
  }
  return work;
}

}  // namespace depot::harness
