#pragma once
// Local mapping (ORB-SLAM2's LocalMapping): takes keyframes from tracking,
// links their map points, culls weak new points, triangulates new points
// with neighbour keyframes, fuses duplicates, runs local bundle adjustment
// and removes redundant keyframes; keeps the place-recognition index and
// hands finished keyframes on (loop closing). Runs in its own thread, or
// synchronously (run_pending) for reproducible runs.
//
// Threads and locks:
// - map.mutex() guards every keyframe and map point (and the Map's sets);
//   the mapper takes it for each step that reads or changes them, one step
//   at a time (process the keyframe, cull points, triangulate with one
//   neighbour, fuse, cull keyframes), so tracking never waits for more than
//   one step; each step re-checks that its keyframes are not bad. Local
//   bundle adjustment takes it itself, around collecting and writing back.
// - The queue, the thread, pausing and failures are a KeyFrameWorker's
//   (its own mutex); loop closing holds the thread between keyframes while
//   it corrects the map (pause()/resume()).
// - stats_mutex_ guards stats_. It is taken after the map lock when both
//   are held (never the other way), and held only briefly.
// - recent_points_ belongs to whichever thread processes keyframes: the
//   mapping thread (threaded) or the caller of run_pending (synchronous).
//   reset() touches it only once the mapper is idle.
// - An exception while processing a keyframe stops mapping: it is kept
//   and rethrown to the tracking side as one depot::Error by
//   throw_if_failed() ("local mapping: <what>"); System::track() and
//   finish() call it. A failed mapper counts as idle and drops new keyframes.
#include <atomic>
#include <list>

#include "common/mutex.h"
#include "slam/data/map.h"
#include "slam/mapping/keyframe_sink.h"
#include "slam/mapping/keyframe_worker.h"

namespace depot::slam {

class KeyFrameDatabase;

struct LocalMapperStats {
  long keyframes = 0;
  long points_created = 0;
  long points_culled = 0;
  long keyframes_culled = 0;
  double ba_ms = 0;
};

class LocalMapper : public KeyFrameSink {
 public:
  // `places` (may be null) receives each processed keyframe with its bag of
  // words, and loses culled ones.
  LocalMapper(Map& map, bool threaded, KeyFrameDatabase* places = nullptr);
  ~LocalMapper() override;

  void insert_keyframe(KeyFrame* kf) override;
  bool idle() const override;
  size_t queued() const override;
  void interrupt_ba() override { abort_ba_ = true; }

  // Synchronous mode: processes every queued keyframe now; a failure is
  // thrown at once (as throw_if_failed).
  void run_pending();
  // Throws depot::Error("local mapping: <what>") once processing a keyframe
  // has thrown; again on every later call.
  void throw_if_failed() const;
  // Waits until idle, then drops queued keyframes and recent points (after
  // the map was cleared).
  void reset();
  // Threaded mode: finishes the queue and stops the thread.
  void stop();
  // Holds the mapping thread between keyframes (a loop correction moves
  // the map under it): returns once no keyframe is being processed; queued
  // keyframes wait until resume().
  void pause();
  void resume();
  // Receives every keyframe mapping has finished and kept (loop closing).
  void set_next(KeyFrameSink* next) { next_ = next; }
  LocalMapperStats stats() const;

 private:
  void process(KeyFrame* kf);
  void process_new_keyframe(KeyFrame* kf);
  void cull_map_points(KeyFrame* kf) DEPOT_REQUIRES(map_.mutex());
  void create_new_map_points(KeyFrame* kf) DEPOT_EXCLUDES(map_.mutex());  // locks per neighbour
  void search_in_neighbors(KeyFrame* kf);
  void cull_keyframes(KeyFrame* kf) DEPOT_REQUIRES(map_.mutex());

  Map& map_;
  KeyFrameDatabase* places_;
  std::atomic<bool> abort_ba_{false};
  KeyFrameSink* next_ = nullptr;
  std::list<MapPoint*> recent_points_;
  mutable Mutex stats_mutex_;
  LocalMapperStats stats_ DEPOT_GUARDED_BY(stats_mutex_);
  KeyFrameWorker worker_;  // last: its thread may call process() at once
};

// Holds local mapping paused for its own lifetime (LocalMapper::pause on
// construction, resume on destruction), so a correction that throws cannot
// leave mapping paused for good.
class MappingPause {
 public:
  explicit MappingPause(LocalMapper& mapper) : mapper_(mapper) { mapper_.pause(); }
  ~MappingPause() { mapper_.resume(); }
  MappingPause(const MappingPause&) = delete;
  MappingPause& operator=(const MappingPause&) = delete;

 private:
  LocalMapper& mapper_;
};

}  // namespace depot::slam
