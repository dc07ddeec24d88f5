#pragma once
// Loop closing (ORB-SLAM2's LoopClosing, for RGB-D: scale is measured, so
// corrections are rigid). For each keyframe local mapping finishes:
//   1. detection: keyframes not connected to it that look like it (bag of
//      words), consistent over three consecutive keyframes;
//   2. geometry: BoW-guided matches to a candidate's map points, a rigid
//      transform from 3-D/3-D pairs with RANSAC (PnP from 3-D/2-D pairs when
//      kf knows too few of its points), pose optimisation, then the
//      loop's map points projected for more matches (>= 40 to accept);
//   3. correction: local mapping paused, the keyframe and its covisibles
//      moved to the loop's pose with their points, duplicate points fused,
//      and the essential graph (spanning tree, loop edges, strong
//      covisibility) optimised; every point moves with its keyframe. Frames'
//      trajectory entries hang off keyframes and follow;
//   4. global bundle adjustment of the whole map (GlobalAdjuster, its own
//      thread; a newer loop aborts it).
// A candidate in another map of the atlas (map.h) is a merge, not a loop
// (ORB-SLAM3's map merging): found and computed as above (the two maps'
// frames are unrelated, so no plausibility bound applies), then confirmed by
// kf's best covisibles, which must find the other map's points where the
// same transform puts them. The smaller map is then moved rigidly into the
// larger one's frame, duplicate points fused across the seam, and the global
// bundle adjustment welds it.
//
// Threading: in threaded mode the closer runs in its own thread (a
// KeyFrameWorker), fed by local mapping. It holds the map mutex while it
// detects, computes and corrects; it pauses local mapping
// (LocalMapper::pause) before correcting, so no bundle adjustment writes
// back poses computed before the correction. stats_mutex_ guards the
// statistics (closures_, refused_). The detection state belongs to the
// worker's thread. In synchronous mode run_pending() does the work on the
// caller's thread.
#include <exception>
#include <map>
#include <set>
#include <vector>

#include "common/mutex.h"
#include "slam/data/map.h"
#include "slam/loop/global_adjuster.h"
#include "slam/mapping/keyframe_sink.h"
#include "slam/mapping/keyframe_worker.h"

namespace depot::slam {

class KeyFrameDatabase;
class LocalMapper;

struct LoopCloserParams {
  int keyframes_between_loops = 10;  // no detection this soon after the last loop
  int consistency = 3;               // consecutive keyframes that must agree
  int min_bow_matches = 20;
  int min_rigid_inliers = 20;
  int min_loop_matches = 40;
  int essential_min_weight = 100;  // covisibility kept in the essential graph
  // A depot repeats its racks: two places metres apart can look alike to
  // the words and to the geometry. A loop is believed only when the
  // correction it asks for is drift that tracking could have made: at most
  // max_correction_m plus drift_per_m times the path travelled (through the
  // keyframes) since the matched keyframe, in translation; in rotation
  // max_rotation_rad plus rotation_per_m per metre.
  double max_correction_m = 0.3;
  double drift_per_m = 0.05;
  double max_rotation_rad = 0.1;
  double rotation_per_m = 0.01;
  // Bundle adjustment of the whole map after each loop (its own thread);
  // 0 iterations: none.
  int global_ba_iterations = 10;
  // A merge is believed when at least merge_confirmations of kf's best
  // covisibles (merge_neighbours tried) each find merge_neighbour_matches of
  // the other map's points where the transform puts them.
  int merge_neighbours = 5;
  int merge_confirmations = 2;
  int merge_neighbour_matches = 20;
};

// One closed loop.
struct LoopClosure {
  long keyframe = 0;        // the keyframe that closed it
  long matched = 0;         // the earlier keyframe it matched
  double timestamp = 0;     // of the closing keyframe
  int matches = 0;          // map-point matches that accepted it
  double correction_m = 0;  // how far the closing keyframe moved
  double path_m = 0;        // path travelled between the two keyframes
  // A merge of two maps of the atlas: the map that moved and the one it
  // joined, and how many keyframes moved (correction_m and path_m are 0).
  bool merge = false;
  int moved_map = -1, into_map = -1;
  int moved_keyframes = 0;
};

class LoopCloser : public KeyFrameSink {
 public:
  LoopCloser(Map& map, KeyFrameDatabase& places, LocalMapper& mapper, bool threaded,
             const LoopCloserParams& params = {});
  ~LoopCloser() override;

  void insert_keyframe(KeyFrame* kf) override;
  bool idle() const override;
  size_t queued() const override;
  void interrupt_ba() override {}

  // Synchronous mode: processes every queued keyframe now.
  void run_pending();
  // Forgets queued keyframes and detection state (after the map was cleared).
  void reset();
  // Threaded mode: finishes the queue and a running global adjustment, and
  // stops the threads.
  void stop();
  // The first exception the thread (or the global adjustment) threw (null
  // when none); the thread stops then.
  std::exception_ptr failure() const;
  std::vector<LoopClosure> closures() const;
  // Global bundle adjustments applied.
  int global_adjustments() const { return global_.completed(); }
  // Loops found but refused as implausible corrections (look-alike places).
  int refused() const;
  // Merges found but not confirmed by the keyframe's neighbours.
  int unconfirmed_merges() const;

 private:
  struct Loop;
  void process(KeyFrame* kf);
  bool detect(KeyFrame* kf, std::vector<KeyFrame*>& candidates) DEPOT_REQUIRES(map_.mutex());
  bool compute_transform(KeyFrame* kf, const std::vector<KeyFrame*>& candidates, Loop& loop)
      DEPOT_REQUIRES(map_.mutex());
  // Whether moving kf to T_cw is drift it could have gathered since `matched`.
  bool plausible_correction(const KeyFrame& kf, const KeyFrame& matched, const Pose& T_cw) const
      DEPOT_REQUIRES(map_.mutex());
  bool correct(KeyFrame* kf, Loop& loop)
      DEPOT_EXCLUDES(map_.mutex());  // false when a keyframe turned bad
  // Whether kf's covisibles agree with a merge's transform (see above).
  bool confirmed_by_neighbours(KeyFrame* kf, const Loop& loop) const DEPOT_REQUIRES(map_.mutex());
  bool merge(KeyFrame* kf, Loop& loop)
      DEPOT_EXCLUDES(map_.mutex());  // false when a keyframe turned bad
  // Replaces kf's points by the loop's where they matched and fuses the
  // loop's points into `connected`; returns the covisibility links that
  // appeared across the loop (kf -> matched among them).
  std::map<KeyFrame*, std::set<KeyFrame*, ById>, ById> fuse_across(
      KeyFrame* kf, const Loop& loop, const std::vector<KeyFrame*>& connected)
      DEPOT_REQUIRES(map_.mutex());
  void optimize_essential_graph(KeyFrame* kf, KeyFrame* matched,
                                const std::map<KeyFrame*, Pose, ById>& original,
                                const std::map<KeyFrame*, std::set<KeyFrame*, ById>, ById>& links)
      DEPOT_REQUIRES(map_.mutex());

  Map& map_;
  KeyFrameDatabase& places_;
  LocalMapper& mapper_;
  LoopCloserParams params_;
  // Detection state: groups of keyframes and for how many consecutive
  // keyframes each has been seen (ORB-SLAM2's consistent groups).
  std::vector<std::pair<std::set<KeyFrame*, ById>, int>> consistent_groups_;
  long last_loop_keyframe_ = -1;

  mutable Mutex stats_mutex_;
  std::vector<LoopClosure> closures_ DEPOT_GUARDED_BY(stats_mutex_);
  int implausible_ DEPOT_GUARDED_BY(stats_mutex_) = 0;  // loops refused by plausible_correction
  int unconfirmed_merges_ DEPOT_GUARDED_BY(stats_mutex_) =
      0;  // merges kf's covisibles did not confirm
  GlobalAdjuster global_;
  KeyFrameWorker worker_;  // last: its thread may call process() at once
};

}  // namespace depot::slam
