#pragma once
// The paper's two-thread front end, run ahead: a detector runs in its own
// thread on a small FIFO of frames, so the caller can submit frame k+1 while
// it still tracks frame k and collect each frame's boxes by its index.
//
// Threads: the caller's thread calls submit() and wait(); the worker thread
// runs the detector. All shared state (the job queue, results, errors, the
// stop flag) is guarded by `mutex_`; the detector and the optional person
// segmenter are used by the worker only (after construction). A job's
// results (boxes, mask, error) are handed over by moving them into the job
// under `mutex_`: the worker keeps no copy, so nothing it still holds is
// shared with the waiter after the lock is released.
#include <condition_variable>
#include <deque>
#include <exception>
#include <thread>
#include <vector>

#include "common/mutex.h"
#include "slam/detect/detection.h"
#include "slam/detect/person_segmenter.h"

namespace depot::slam {

class DetectionThread {
 public:
  // Submitting more than `max_jobs` frames that are not yet waited for is an
  // error (the caller looks ahead too far or never waits).
  // `segmenter` (optional, not owned): also computes each frame's person
  // mask in the worker, after the detector, so its cost is hidden too.
  explicit DetectionThread(Detector& detector, size_t max_jobs = 4,
                           PersonSegmenter* segmenter = nullptr);
  ~DetectionThread();  // finishes the running job, drops the queued ones
  DetectionThread(const DetectionThread&) = delete;
  DetectionThread& operator=(const DetectionThread&) = delete;

  // Queues detection of frame `frame_index`; jobs run in submission order.
  // Submitting a frame that is already queued, running or done but not yet
  // waited for does nothing. Lifetime: the image is shared, not copied (the
  // job holds a cv::Mat header on the caller's pixels), so the caller must
  // neither write into those pixels nor free them (for a Mat over external
  // data) until wait() for this frame has returned. Throws depot::Error when
  // `max_jobs` frames are already queued.
  void submit(const cv::Mat& bgr, double timestamp, long frame_index);
  // The detections of frame `frame_index`, blocking until its job is done,
  // and forgets that frame along with any earlier frames never waited for
  // (queued ones are dropped unrun). `waited_ms`: how long the caller
  // blocked; `detect_ms`: the detector's own time on this frame. Rethrows
  // the detector's error for this frame; throws depot::Error for a frame
  // that was not submitted.
  // With a segmenter, `person_mask` receives the frame's person mask (CV_8U,
  // 255 = person) and `segment_ms` its time.
  std::vector<Detection> wait(long frame_index, double* waited_ms = nullptr,
                              double* detect_ms = nullptr, cv::Mat* person_mask = nullptr,
                              double* segment_ms = nullptr);

  // Frames submitted and not yet waited for.
  size_t queued() const;

 private:
  enum class JobState { kQueued, kRunning, kDone };
  struct Job {
    long index = 0;
    cv::Mat image;
    double timestamp = 0;
    JobState state = JobState::kQueued;
    std::vector<Detection> result;
    double detect_ms = 0;
    cv::Mat person_mask;
    double segment_ms = 0;
    std::exception_ptr error;
  };
  Job* find(long frame_index) DEPOT_REQUIRES(mutex_);
  Job* first_queued() DEPOT_REQUIRES(mutex_);  // the oldest job not yet started
  void run();

  Detector& detector_;          // worker thread only
  PersonSegmenter* segmenter_;  // worker thread only; may be null
  const size_t max_jobs_;
  mutable Mutex mutex_;
  std::condition_variable cv_;
  std::deque<Job> jobs_ DEPOT_GUARDED_BY(mutex_);  // submission order; frame indices unique
  bool stop_ DEPOT_GUARDED_BY(mutex_) = false;
  std::thread thread_;  // last: starts after the members above exist
};

}  // namespace depot::slam
