#pragma once
// The paper's two-thread front end: a detector runs on each incoming frame
// in its own thread while the tracker extracts ORB features, and hands its
// boxes over for the same frame.
#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>

#include "slam/detect/detection.h"

namespace depot::slam {

class DetectionThread {
 public:
  explicit DetectionThread(Detector& detector);
  ~DetectionThread();
  DetectionThread(const DetectionThread&) = delete;
  DetectionThread& operator=(const DetectionThread&) = delete;

  // Starts detection on a frame (the image is shared, not copied: keep it
  // unchanged until wait() returns).
  void submit(const cv::Mat& bgr, double timestamp, long frame_index);
  // The detections of the submitted frame. `waited_ms`: how long the caller
  // blocked; `detect_ms`: the detector's own time. Rethrows detector errors.
  std::vector<Detection> wait(double* waited_ms = nullptr, double* detect_ms = nullptr);

 private:
  void run();
  Detector& detector_;
  std::mutex mutex_;
  std::condition_variable cv_;
  bool has_job_ = false, done_ = false, stop_ = false;
  cv::Mat image_;
  double timestamp_ = 0;
  long index_ = 0;
  std::vector<Detection> result_;
  double detect_ms_ = 0;
  std::exception_ptr error_;
  std::thread thread_;
};

}  // namespace depot::slam
