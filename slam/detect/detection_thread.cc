#include "slam/detect/detection_thread.h"

#include <algorithm>
#include <chrono>
#include <string>

#include "common/error.h"

namespace depot::slam {

DetectionThread::DetectionThread(Detector& detector, size_t max_jobs, PersonSegmenter* segmenter)
    : detector_(detector),
      segmenter_(segmenter),
      max_jobs_(std::max<size_t>(1, max_jobs)),
      thread_([this] { run(); }) {}

DetectionThread::~DetectionThread() {
  {
    MutexLock lock(mutex_);
    stop_ = true;
  }
  cv_.notify_all();
  thread_.join();
}

DetectionThread::Job* DetectionThread::find(long frame_index) {
  for (Job& job : jobs_)
    if (job.index == frame_index) return &job;
  return nullptr;
}

DetectionThread::Job* DetectionThread::first_queued() {
  for (Job& job : jobs_)
    if (job.state == JobState::kQueued) return &job;
  return nullptr;
}

void DetectionThread::submit(const cv::Mat& bgr, double timestamp, long frame_index) {
  {
    MutexLock lock(mutex_);
    if (find(frame_index)) return;
    if (jobs_.size() >= max_jobs_)
      fail("frame " + std::to_string(frame_index), "detection queue full (" +
                                                       std::to_string(jobs_.size()) +
                                                       " frames submitted and not waited for)");
    Job job;
    job.index = frame_index;
    job.image = bgr;  // a header on the caller's pixels, not a copy
    job.timestamp = timestamp;
    jobs_.push_back(std::move(job));
  }
  cv_.notify_all();
}

std::vector<Detection> DetectionThread::wait(long frame_index, double* waited_ms, double* detect_ms,
                                             cv::Mat* person_mask, double* segment_ms) {
  const auto t0 = std::chrono::steady_clock::now();
  MutexLock lock(mutex_);
  if (!find(frame_index))
    fail("frame " + std::to_string(frame_index), "was not submitted for detection");
  Job* job = find(frame_index);
  while (job && job->state != JobState::kDone) {
    mutex_.wait(cv_);
    job = find(frame_index);
  }
  if (!job) fail("frame " + std::to_string(frame_index), "was waited for twice at once");
  if (waited_ms)
    *waited_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (detect_ms) *detect_ms = job->detect_ms;
  if (person_mask) *person_mask = job->person_mask;
  if (segment_ms) *segment_ms = job->segment_ms;
  std::vector<Detection> result = std::move(job->result);
  const std::exception_ptr error = job->error;
  // Forget this frame and earlier ones never waited for (not the one running).
  jobs_.erase(std::remove_if(jobs_.begin(), jobs_.end(),
                             [&](const Job& j) {
                               return j.index <= frame_index && j.state != JobState::kRunning;
                             }),
              jobs_.end());
  lock.unlock();
  if (error) std::rethrow_exception(error);
  return result;
}

size_t DetectionThread::queued() const {
  MutexLock lock(mutex_);
  return jobs_.size();
}

void DetectionThread::run() {
  while (true) {
    cv::Mat image;
    double timestamp = 0;
    long index = 0;
    {
      MutexLock lock(mutex_);
      Job* next = first_queued();
      while (!stop_ && !next) {
        mutex_.wait(cv_);
        next = first_queued();
      }
      if (stop_) return;
      next->state = JobState::kRunning;
      image = next->image;
      timestamp = next->timestamp;
      index = next->index;
    }
    std::vector<Detection> result;
    std::exception_ptr error;
    const auto t0 = std::chrono::steady_clock::now();
    try {
      result = detector_.detect(image, timestamp, index);
    } catch (...) {
      error = std::current_exception();
    }
    const auto t1 = std::chrono::steady_clock::now();
    const double ms = std::chrono::duration<double, std::milli>(t1 - t0).count();
    cv::Mat person_mask;
    if (segmenter_ && !error) {
      try {
        person_mask = segmenter_->mask(image).clone();  // the segmenter reuses its buffer
      } catch (...) {
        error = std::current_exception();
      }
    }
    const double segment_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t1).count();
    image.release();
    {
      MutexLock lock(mutex_);
      Job* job = find(index);  // a running job is never erased
      job->image.release();
      job->result = std::move(result);
      // Moved, not copied: the worker keeps no reference to the exception,
      // so the waiter owns it alone once the lock is released (a copy kept
      // here would be released after the waiter read and freed it, ordered
      // only by exception_ptr's refcount inside libstdc++).
      job->error = std::move(error);
      job->detect_ms = ms;
      job->person_mask = std::move(person_mask);
      job->segment_ms = segment_ms;
      job->state = JobState::kDone;
    }
    cv_.notify_all();
  }
}

}  // namespace depot::slam
