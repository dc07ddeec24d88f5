#pragma once
// A queue of keyframes processed one at a time, in order, either on a thread
// of its own (threaded) or on the caller's thread (run_pending, synchronous
// mode: reproducible runs). Local mapping and loop closing are each one
// worker with their own `process` step.
//
// Threads and locks: mutex_ guards queue_, paused_, stop_ and failure_;
// busy_ is set by the worker thread while a keyframe is processed. `process`
// runs without mutex_ held, so it may call queued() / idle(). An exception
// thrown by `process` stops the worker: it is kept (failure()), the queue is
// dropped, a failed worker counts as idle and refuses new keyframes.
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <functional>
#include <thread>

#include "common/mutex.h"

namespace depot::slam {

class KeyFrame;

class KeyFrameWorker {
 public:
  using Process = std::function<void(KeyFrame*)>;

  KeyFrameWorker(bool threaded, Process process);
  ~KeyFrameWorker();
  KeyFrameWorker(const KeyFrameWorker&) = delete;
  KeyFrameWorker& operator=(const KeyFrameWorker&) = delete;

  // Queues kf; false (kf dropped) once the worker has failed.
  bool push(KeyFrame* kf);
  // Failed, or nothing queued and nothing being processed.
  bool idle() const;
  size_t queued() const;
  // Synchronous mode: processes every queued keyframe now; rethrows the
  // exception of the step that failed.
  void run_pending();
  // Drops queued keyframes and waits until none is being processed.
  void clear();
  // Holds the thread between keyframes: returns once none is being
  // processed; queued keyframes wait until resume(). request_pause() only
  // asks (a keyframe being processed goes on); pause_requested() tells a
  // step that it should finish early.
  void request_pause();
  void pause();
  void resume();
  bool pause_requested() const;
  // Threaded mode: finishes the queue and joins the thread.
  void stop();
  // The exception that stopped the worker (null when none).
  std::exception_ptr failure() const;

 private:
  void thread_main();
  // process_ with its exception kept; false when it threw.
  bool process_guarded(KeyFrame* kf);

  const bool threaded_;
  const Process process_;
  mutable Mutex mutex_;
  std::condition_variable cv_;
  std::deque<KeyFrame*> queue_ DEPOT_GUARDED_BY(mutex_);
  std::atomic<bool> busy_{false};
  bool paused_ DEPOT_GUARDED_BY(mutex_) = false;
  bool stop_ DEPOT_GUARDED_BY(mutex_) = false;
  std::exception_ptr failure_ DEPOT_GUARDED_BY(mutex_);
  std::thread thread_;  // started last, once every member above exists
};

}  // namespace depot::slam
