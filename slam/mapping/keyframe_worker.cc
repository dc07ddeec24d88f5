#include "slam/mapping/keyframe_worker.h"

#include <chrono>
#include <utility>

namespace depot::slam {

KeyFrameWorker::KeyFrameWorker(bool threaded, Process process)
    : threaded_(threaded), process_(std::move(process)) {
  if (threaded_) thread_ = std::thread([this] { thread_main(); });
}

KeyFrameWorker::~KeyFrameWorker() {
  stop();
}

bool KeyFrameWorker::push(KeyFrame* kf) {
  {
    MutexLock lock(mutex_);
    if (failure_) return false;  // nobody would process it
    queue_.push_back(kf);
  }
  cv_.notify_one();
  return true;
}

bool KeyFrameWorker::idle() const {
  MutexLock lock(mutex_);
  return failure_ || (queue_.empty() && !busy_);
}

size_t KeyFrameWorker::queued() const {
  MutexLock lock(mutex_);
  return queue_.size();
}

std::exception_ptr KeyFrameWorker::failure() const {
  MutexLock lock(mutex_);
  return failure_;
}

void KeyFrameWorker::run_pending() {
  while (true) {
    KeyFrame* kf = nullptr;
    {
      MutexLock lock(mutex_);
      if (failure_) std::rethrow_exception(failure_);
      if (queue_.empty()) return;
      kf = queue_.front();
      queue_.pop_front();
    }
    process_guarded(kf);
  }
}

void KeyFrameWorker::clear() {
  while (true) {
    {
      MutexLock lock(mutex_);
      queue_.clear();
      if (!busy_) return;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

void KeyFrameWorker::request_pause() {
  MutexLock lock(mutex_);
  paused_ = true;
}

bool KeyFrameWorker::pause_requested() const {
  MutexLock lock(mutex_);
  return paused_;
}

void KeyFrameWorker::pause() {
  request_pause();
  while (busy_) std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

void KeyFrameWorker::resume() {
  {
    MutexLock lock(mutex_);
    paused_ = false;
  }
  cv_.notify_one();
}

void KeyFrameWorker::stop() {
  if (!threaded_ || !thread_.joinable()) return;
  {
    MutexLock lock(mutex_);
    stop_ = true;
    paused_ = false;  // a paused worker would never see its queue end
  }
  cv_.notify_one();
  thread_.join();
}

void KeyFrameWorker::thread_main() {
  while (true) {
    KeyFrame* kf = nullptr;
    {
      MutexLock lock(mutex_);
      while (!stop_ && (paused_ || queue_.empty())) mutex_.wait(cv_);
      if (queue_.empty()) return;  // stop requested and nothing left
      kf = queue_.front();
      queue_.pop_front();
      busy_ = true;
    }
    const bool ok = process_guarded(kf);
    busy_ = false;
    if (!ok) return;  // the failure waits for failure() / run_pending()
  }
}

bool KeyFrameWorker::process_guarded(KeyFrame* kf) {
  try {
    process_(kf);
    return true;
  } catch (...) {
    MutexLock lock(mutex_);
    failure_ = std::current_exception();
    queue_.clear();
    return false;
  }
}

}  // namespace depot::slam
