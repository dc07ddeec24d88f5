#pragma once
// The SLAM system: feed (rgb, depth, timestamp), get the camera pose and
// tracking state. Owns the ORB extractor, the place-recognition index, the
// optional keypoint filter (the dynamic-rejection seam), the tracker, the map and local mapping.
//
// Threads and locks: one thread calls every method of a System (it is the
// tracking thread); local mapping and loop closing may run in threads of their own. The map
// (keyframes, points) is guarded by map.mutex(), which the tracker holds
// for a whole frame and every reader here takes (see tracker.h and
// local_mapper.h for who takes it when). An exception in the mapping thread
// is rethrown by the next track() or finish() as one depot::Error
// ("local mapping: ...").
#include <deque>
#include <memory>
#include <vector>

#include <opencv2/core.hpp>

#include "common/tum_io.h"
#include "slam/data/map.h"
#include "slam/feature/orb_extractor.h"
#include "slam/io/settings.h"
#include "slam/loop/loop_closer.h"
#include "slam/mapping/local_mapper.h"
#include "slam/place/keyframe_database.h"
#include "slam/track/keypoint_filter.h"
#include "slam/track/tracker.h"

namespace depot::slam {

struct FrameTiming {
  double extract_ms = 0;
  double filter_ms = 0;
  double track_ms = 0;  // matching + pose optimisation + keyframe decision
  double total_ms = 0;
};

// A tracked frame's pose in the coordinate frame of its atlas map, the map
// numbered as frame_states() numbers it (0 = the main map).
struct AtlasPose {
  StampedPose pose;
  int map = 0;
};

struct TrackResult {
  TrackingState state = TrackingState::kNotInitialized;
  Pose T_wc = Pose::Identity();  // valid when state is OK or RELOCALIZED
  int keypoints = 0;             // extracted
  int kept = 0;                  // after the keypoint filter
  TrackingStats stats;
  FrameTiming timing;
};

class System {
 public:
  // `filter` may be null (plain ORB-SLAM2); it is not owned. Loads the
  // settings' vocabulary (depot::Error naming the file when it cannot).
  explicit System(const SlamSettings& settings, KeypointFilter* filter = nullptr);
  ~System();

  // bgr: CV_8UC3; depth: CV_32F metres (0 = none), same size as the camera.
  TrackResult track(const cv::Mat& bgr, const cv::Mat& depth, double timestamp);
  // Hands a frame over before its turn so the filter can start on it early
  // (KeypointFilter::look_ahead; the rejection filter's detector runs on it
  // while the frames before it are tracked). Frames are handed over in
  // tracking order, starting with the next frame track() will get: each gets
  // the id its track() call will assign. track() must then be given the same
  // frames in that order (checked by timestamp; depot::Error otherwise). The
  // images are shared, not copied: keep their pixels unchanged until the
  // frame has been tracked. Does nothing else without a filter.
  void look_ahead(const cv::Mat& bgr, const cv::Mat& depth, double timestamp);
  // Lets local mapping finish its queue (call before reading trajectories).
  // Throws depot::Error when local mapping failed.
  void finish();

  // Map reuse (slam/io/map_file.h). load_map: before the first frame, the
  // saved map becomes this system's (its vocabulary, camera and ORB
  // pyramid must be this run's), and the first frame relocalises in it.
  // save_map: every map of the atlas as it is (call finish() first); a
  // staged write.
  // start_localisation: from the next frame on, track against the map as it
  // is without changing it (no keyframes, no points, no reset), starting
  // with a relocalisation; depot::Error when the map is empty.
  void load_map(const std::string& path);
  void save_map(const std::string& path) const;
  void start_localisation();

  // Camera-to-world pose of every tracked frame (state NEW_MAP, OK or
  // RELOCALIZED, tracking_state.h) in the main map of the atlas (the one
  // holding most tracked frames, after merges). Frames without a pose (not
  // initialised, lost, tracked in a map a reset abandoned or in another map
  // of the atlas) are left out: frame_states() says what became of them.
  std::vector<StampedPose> trajectory() const;
  // The state of every frame given so far, in order: one entry per track()
  // call. Its tracked entries are the trajectory's frames; frames tracked
  // in another map of the atlas are OTHER_MAP. Frames with a pose carry
  // their map's number (0 = main, 1.. the others by frames held).
  std::vector<StampedFrameState> frame_states() const;
  // Every frame tracked in any map of the atlas, each in its map's frame.
  std::vector<AtlasPose> atlas_trajectory() const;
  // Keyframes of the main map.
  std::vector<StampedPose> keyframe_trajectory() const;
  // Keyframes of every atlas map holding tracked frames, indexed by the map
  // numbers of frame_states() (0 = main): each in its own map's frame.
  std::vector<std::vector<StampedPose>> keyframe_trajectories() const;
  // Maps in the atlas (those with keyframes).
  int maps() const;
  size_t n_keyframes() const;
  size_t n_map_points() const;
  LocalMapperStats mapping_stats() const { return mapper_.stats(); }
  std::vector<LoopClosure> loop_closures() const { return loop_closer_.closures(); }
  int loops_refused() const { return loop_closer_.refused(); }
  int merges_unconfirmed() const { return loop_closer_.unconfirmed_merges(); }
  // Young maps merged into an older one because a frame relocalised there.
  int maps_rejoined() const { return tracker_.rejoined(); }
  // Global bundle adjustments applied after loops.
  int global_adjustments() const { return loop_closer_.global_adjustments(); }
  const SlamSettings& settings() const { return settings_; }
  int resets() const { return resets_; }

 private:
  void check_images(const cv::Mat& bgr, const cv::Mat& depth, long frame_id) const;
  // Rethrows a worker thread's exception as one depot::Error.
  void check_workers() const;

  SlamSettings settings_;
  KeypointFilter* filter_;
  ScaleLevels levels_;
  OrbExtractor extractor_;
  mutable Map map_;
  KeyFrameDatabase places_;
  LocalMapper mapper_;
  LoopCloser loop_closer_;
  Tracker tracker_;
  long next_frame_id_ = 0;
  // Timestamps of the frames handed over by look_ahead() and not yet
  // tracked; the first has id next_frame_id_, the next +1, ...
  std::deque<double> ahead_;
  int resets_ = 0;
};

}  // namespace depot::slam
