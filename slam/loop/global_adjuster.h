#pragma once
// Global bundle adjustment after a loop closure, in a thread of its own
// (ORB-SLAM2's RunGlobalBundleAdjustment). The essential graph spreads a
// loop's error over the keyframes; this then refines every keyframe and
// point against all their observations.
//
// The map keeps growing while it solves, so the result is applied with local
// mapping paused and the map locked: solved keyframes and points take their
// new poses; keyframes made meanwhile move with their parent in the spanning
// tree (their pose relative to it kept), points made meanwhile with their
// reference keyframe. A newer loop aborts a running adjustment and starts
// another.
//
// Threads and locks: start(), stop(), running() and failure() are called by
// the loop closer's thread (or the system's); mutex_ guards thread_,
// running_, completed_ and failure_. The adjusting thread takes the map lock
// only to collect and to apply (optimize/optimizer.h). Synchronous mode
// (threaded = false) runs the adjustment inside start(), for reproducible
// runs.
#include <atomic>
#include <exception>
#include <thread>

#include "common/mutex.h"
#include "slam/data/map.h"
#include "slam/optimize/optimizer.h"

namespace depot::slam {

class LocalMapper;

// Writes a finished adjustment into the map: solved keyframes and points
// take the result; keyframes missing from it move with their spanning-tree
// parent, points with their reference keyframe. The caller holds the map
// lock (and has paused local mapping).
void apply_global_adjustment(Map& map, const GlobalBaResult& result) DEPOT_REQUIRES(map.mutex());

class GlobalAdjuster {
 public:
  GlobalAdjuster(Map& map, LocalMapper& mapper, bool threaded, int iterations = 10);
  ~GlobalAdjuster();
  GlobalAdjuster(const GlobalAdjuster&) = delete;
  GlobalAdjuster& operator=(const GlobalAdjuster&) = delete;

  // Adjusts the whole map (after a loop closure); a running adjustment is
  // aborted first (its result dropped).
  void start();
  // Aborts a running adjustment and waits for its thread.
  void abort();
  // Waits for a running adjustment to finish and apply its result.
  void wait();
  bool running() const;
  // Adjustments applied so far.
  int completed() const;
  // The first exception the adjusting thread threw (null when none).
  std::exception_ptr failure() const;

 private:
  void run();

  Map& map_;
  LocalMapper& mapper_;
  const bool threaded_;
  const int iterations_;
  std::atomic<bool> abort_{false};
  mutable Mutex mutex_;
  std::thread thread_ DEPOT_GUARDED_BY(mutex_);
  bool running_ DEPOT_GUARDED_BY(mutex_) = false;
  int completed_ DEPOT_GUARDED_BY(mutex_) = 0;
  std::exception_ptr failure_ DEPOT_GUARDED_BY(mutex_);
};

}  // namespace depot::slam
