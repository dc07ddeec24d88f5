#include "slam/detect/detection_thread.h"

#include <chrono>

namespace depot::slam {

DetectionThread::DetectionThread(Detector& detector)
    : detector_(detector), thread_([this] { run(); }) {}

DetectionThread::~DetectionThread() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  cv_.notify_all();
  thread_.join();
}

void DetectionThread::submit(const cv::Mat& bgr, double timestamp, long frame_index) {
  std::lock_guard<std::mutex> lock(mutex_);
  image_ = bgr;
  timestamp_ = timestamp;
  index_ = frame_index;
  has_job_ = true;
  done_ = false;
  error_ = nullptr;
  cv_.notify_all();
}

std::vector<Detection> DetectionThread::wait(double* waited_ms, double* detect_ms) {
  const auto t0 = std::chrono::steady_clock::now();
  std::unique_lock<std::mutex> lock(mutex_);
  cv_.wait(lock, [&] { return done_ || !has_job_; });
  if (waited_ms)
    *waited_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (detect_ms) *detect_ms = detect_ms_;
  if (error_) std::rethrow_exception(error_);
  has_job_ = false;
  return std::move(result_);
}

void DetectionThread::run() {
  while (true) {
    cv::Mat image;
    double t;
    long index;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      cv_.wait(lock, [&] { return stop_ || (has_job_ && !done_); });
      if (stop_) return;
      image = image_;
      t = timestamp_;
      index = index_;
    }
    std::vector<Detection> result;
    std::exception_ptr error;
    const auto t0 = std::chrono::steady_clock::now();
    try {
      result = detector_.detect(image, t, index);
    } catch (...) {
      error = std::current_exception();
    }
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    {
      std::lock_guard<std::mutex> lock(mutex_);
      result_ = std::move(result);
      error_ = error;
      detect_ms_ = ms;
      done_ = true;
    }
    cv_.notify_all();
  }
}

}  // namespace depot::slam
