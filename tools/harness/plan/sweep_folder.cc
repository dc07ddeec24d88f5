#include "tools/harness/plan/sweep_folder.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>
#include <thread>

#include "common/error.h"
#include "tools/harness/plan/sweep_job_state.h"

namespace fs = std::filesystem;

namespace depot::harness {

SweepFolderLock::SweepFolderLock(const std::string& root, const std::string& scheduler)
    : scheduler_(scheduler) {
  const std::string path = (fs::path(root) / ".lock").string();
  fd_ = open(path.c_str(), O_CREAT | O_RDWR, 0644);
  if (fd_ < 0) fail(path, "cannot create the sweep's lock file");
  // `sweep status` holds the lock shared for a moment to see whether a
  // runner is there: a few tries before another runner is assumed.
  for (int attempt = 0; flock(fd_, LOCK_EX | LOCK_NB) != 0; ++attempt) {
    if (errno != EWOULDBLOCK || attempt == 20) {
      close(fd_);
      fail(root, "another `depot sweep` is running in this folder");
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  write_owner({});
}

SweepFolderLock::~SweepFolderLock() {
  if (ftruncate(fd_, 0) != 0) {
    // Only `sweep status` reads it, and only while the lock is held.
  }
  close(fd_);
}

void SweepFolderLock::set_running(const std::set<std::string>& job_ids) {
  write_owner(job_ids);
}

void SweepFolderLock::write_owner(const std::set<std::string>& running) {
  std::string text = scheduler_ + " " + std::to_string(getpid()) + "\n";
  for (const auto& id : running) text += id + "\n";
  // New text first, then cut to its length: a reader sees no empty file.
  if (pwrite(fd_, text.data(), text.size(), 0) != static_cast<ssize_t>(text.size()) ||
      ftruncate(fd_, static_cast<off_t>(text.size())) != 0) {
    // Only `sweep status` reads it: a lock without its note still locks.
  }
}

std::optional<ActiveRunner> active_runner(const std::string& root) {
  const std::string path = (fs::path(root) / ".lock").string();
  const int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return std::nullopt;
  if (flock(fd, LOCK_SH | LOCK_NB) == 0) {  // nobody holds it
    flock(fd, LOCK_UN);
    close(fd);
    return std::nullopt;
  }
  std::string text;
  char buf[4096];
  for (ssize_t n; (n = read(fd, buf, sizeof(buf))) > 0;) text.append(buf, static_cast<size_t>(n));
  close(fd);
  ActiveRunner runner;
  std::istringstream in(text);
  std::string line;
  if (std::getline(in, line)) {
    std::istringstream first(line);
    first >> runner.scheduler >> runner.pid;
  }
  while (std::getline(in, line))
    if (!line.empty()) runner.running.insert(line);
  return runner;
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
  std::map<std::string, bool> render_done;
  for (size_t i = 0; i < plan.jobs.size(); ++i) {
    const SweepJob& job = plan.jobs[i];
    const JobRecordState s = job_record_state(layout, job);
    if (s.state == RecordState::kCorrupt) work.corrupt.push_back({job.id, s.problem});
    const bool done = s.state == RecordState::kDone;
    if (job.kind == JobKind::kRender) {
      render_done[job.id] = done;
    } else if (done) {
      ++work.already_finished;
    } else {
      pending_runs_of[job.dataset_id].push_back(i);
    }
  }
  for (size_t i = 0; i < plan.jobs.size(); ++i) {
    const SweepJob& job = plan.jobs[i];
    if (job.kind != JobKind::kRender) continue;
    auto it = pending_runs_of.find(job.id);
    if (it == pending_runs_of.end() && render_done[job.id]) {
      ++work.already_finished;
      work.datasets_done.push_back(job.id);
      continue;
    }
    // Runs left, or a render without a good record (rendered again, even
    // when its runs are done, so that no bad record stays).
    const bool data_ready = render_done[job.id] && fs::is_directory(layout.dataset_dir(job.id));
    work.already_finished += data_ready;
    work.datasets.push_back(
        {i, !data_ready, it == pending_runs_of.end() ? std::vector<size_t>{} : it->second});
  }
  return work;
}

void warn_corrupt_records(const PendingWork& work) {
  for (const CorruptRecord& c : work.corrupt)
    std::fprintf(stderr,
                 "depot: warning: %s; job %s runs again and its new record replaces this one\n",
                 c.problem.c_str(), c.job_id.c_str());
}

}  // namespace depot::harness
