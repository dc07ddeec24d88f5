#pragma once
// The tracking front end (ORB-SLAM2's Tracking for RGB-D): initialisation
// from depth, constant-velocity motion model with projection matching,
// fallback to the reference keyframe, local-map tracking, keyframe decision
// and relocalisation anywhere in the map (place recognition).
//
// Threads and locks: a Tracker is driven by one thread (the caller of
// System::track), which owns every member below; no other thread touches
// them. Keyframes and map points are shared with local mapping and guarded
// by map.mutex(): track() holds it for the whole frame (every tracking step
// below is DEPOT_REQUIRES it, checked by clang), reset() and every
// reader of map state (trajectory resolution, wants_reset's keyframe count)
// must be called with it held or read a value computed under it. The
// mapper (KeyFrameSink) is called with the map lock held; its methods only
// take its own queue lock, never the map's, so the order is always map
// then queue.
#include <vector>

#include "common/pose.h"
#include "slam/data/frame.h"
#include "slam/data/map.h"
#include "slam/mapping/keyframe_sink.h"
#include "slam/match/orb_matcher.h"
#include "slam/track/tracking_state.h"

namespace depot::slam {

class KeyFrameDatabase;

struct TrackerParams {
  // Keypoints (after rejection) needed to start, 100 of them with depth;
  // ORB-SLAM2 asks 500 of all keypoints, too many once people are removed.
  int min_init_points = 300;
  int max_frames_between_kf = 30;  // ~1 s at 30 Hz
  int min_frames_between_kf = 0;
  // A frame tracked with fewer inliers than this takes a keyframe (once
  // min_frames_between_kf have passed), whatever the reference counts say:
  // under rejection a young map's points are seen by too few keyframes for
  // ORB-SLAM2's ratio to fire, and too few keypoints have depth for its
  // close-point rule, so the map went on thinning until it was lost. The
  // keyframe adds this frame's depth points. 0 = ORB-SLAM2's rules only.
  int weak_inliers = 80;
  int local_map_min_inliers = 30;
  int relocalisation_min_inliers = 50;
  int relocalisation_candidates = 20;  // place-recognition candidates tried, best first
  // A map lost while tiny is reset at once (ORB-SLAM2: <= 5 keyframes). One
  // still young (fewer than young_map_keyframes) that stays lost for
  // young_map_lost_frames frames in a row is reset too (ORB-SLAM3 resets a
  // lost map below 10 keyframes): a few hundred points rarely give
  // relocalisation its 50 inliers, and the camera would stay lost for the
  // rest of the run (walking_xyz seed 2: lost on frame 7 with 6 keyframes,
  // then 293 frames lost).
  int reset_keyframes = 5;
  int young_map_keyframes = 10;
  int young_map_lost_frames = 30;  // ~1 s at 30 Hz
  // The atlas (ORB-SLAM3, map.h): a lost camera that cannot relocalise in
  // any map starts a new map on that frame (when it has the points to), and
  // no map is ever reset: loop closing merges maps that share a place. Off:
  // ORB-SLAM2's behaviour (stay lost; reset young maps as above).
  bool atlas = true;
};

// How the frame's pose was first found (before local-map tracking).
enum class TrackingMethod {
  kNone,               // not initialised and no map started on this frame
  kInitialization,     // a new map started on this frame
  kMotionModel,        // constant velocity from the last frame, projection matching
  kReferenceKeyFrame,  // descriptor matching against the reference keyframe
  kRelocalization,     // tracking was lost: matched against recent keyframes
};

inline const char* tracking_method_name(TrackingMethod m) {
  switch (m) {
    case TrackingMethod::kNone:
      return "none";
    case TrackingMethod::kInitialization:
      return "initialization";
    case TrackingMethod::kMotionModel:
      return "motion_model";
    case TrackingMethod::kReferenceKeyFrame:
      return "reference_keyframe";
    case TrackingMethod::kRelocalization:
      return "relocalization";
  }
  return "?";
}

struct TrackingStats {
  TrackingMethod method = TrackingMethod::kNone;  // the last one tried
  int matches = 0;  // after the first stage (motion model / reference / reloc)
  int inliers = 0;  // after local-map tracking
  int local_points = 0;
  bool new_keyframe = false;
  double match_ms = 0;     // all descriptor matching of the frame
  double optimize_ms = 0;  // all pose optimisation of the frame
};

// One entry per frame given: its state (tracking_state.h) and, for a tracked
// frame, the pose relative to a reference keyframe, so later corrections of
// that keyframe move the frame with it. Untracked frames have no reference.
struct TrajectoryEntry {
  double timestamp = 0;
  KeyFrame* reference = nullptr;
  Pose T_cr = Pose::Identity();
  FrameState state = FrameState::kNotInitialized;
};

class Tracker {
 public:
  // `places` (may be null: a lost tracker then stays lost) finds the
  // keyframes a lost frame may relocalise against, anywhere in the map.
  Tracker(Map& map, KeyFrameSink& mapper, const TrackerParams& params = {},
          KeyFrameDatabase* places = nullptr);

  // Tracks a frame whose features are extracted (and filtered). Takes the map
  // lock for the whole frame.
  TrackingState track(Frame frame, TrackingStats* stats = nullptr) DEPOT_EXCLUDES(map_.mutex());

  TrackingState state() const { return state_; }
  // True when the last frame was lost while the map was still tiny, or
  // (without the atlas) has been lost for a while in a young map
  // (TrackerParams): the system should reset (with the atlas:
  // discard_active_map) and initialise again.
  // Decided inside track() under the map lock (the mapper may cull
  // keyframes meanwhile), so it needs no lock.
  bool wants_reset() const { return reset_wanted_; }
  // Back to NOT_INITIALIZED; frames tracked so far leave the trajectory
  // (they belong to the abandoned map: state ABANDONED). The caller holds
  // the map lock and clears the map.
  void reset() DEPOT_REQUIRES(map_.mutex());
  // The atlas's reset: only the active map is forgotten (Map::discard_map,
  // its keyframes leave `places`), its frames become ABANDONED and a new
  // map begins; other maps keep theirs, and while there are any the next
  // frame relocalises in them before it starts the new map. The caller
  // holds the map lock and has cleared local mapping's and loop closing's
  // queues.
  void discard_active_map() DEPOT_REQUIRES(map_.mutex());
  // The next frame relocalises against the map as it is (a loaded map),
  // anywhere in it, instead of starting one; the atlas starts no new map
  // before one has. The caller holds the map lock.
  void relocalise_in_map() DEPOT_REQUIRES(map_.mutex());
  // The map lock as the tracker names it (the Map it was built on), for a
  // caller that holds that Map's lock: map_mutex().assert_held().
  Mutex& map_mutex() const DEPOT_RETURN_CAPABILITY(map_.mutex()) { return map_.mutex(); }
  // Localisation only: no keyframes or points are made and a lost camera
  // never resets the map.
  void set_localisation_only(bool on) { localisation_only_ = on; }
  bool localisation_only() const { return localisation_only_; }
  const Frame& last_frame() const { return last_; }
  // Young maps merged into an older one by rejoin_older_map.
  int rejoined() const { return rejoined_; }
  // Every frame given so far, in order (tracked or not). Resolving a tracked
  // entry's pose reads its reference keyframe: hold the map lock.
  const std::vector<TrajectoryEntry>& trajectory() const { return trajectory_; }

 private:
  // Enough keypoints, and enough with depth, to start a map on.
  bool can_initialize(const Frame& frame) const DEPOT_REQUIRES(map_.mutex());
  bool initialize(Frame& frame) DEPOT_REQUIRES(map_.mutex());
  // Points of the last frame that local mapping fused into others are
  // replaced by their survivors (ORB-SLAM2's CheckReplacedInLastFrame).
  // Back to NOT_INITIALIZED with no last frame, velocity or local map.
  void forget_motion() DEPOT_REQUIRES(map_.mutex());
  // The frames tracked in map `map_id` (every map when -1) lose their pose:
  // ABANDONED.
  void abandon_frames(int map_id) DEPOT_REQUIRES(map_.mutex());
  void follow_replaced_points_in_last_frame() DEPOT_REQUIRES(map_.mutex());
  bool track_motion_model(Frame& frame, int& matches) DEPOT_REQUIRES(map_.mutex());
  bool track_reference_keyframe(Frame& frame, int& matches) DEPOT_REQUIRES(map_.mutex());
  // Relocalises in any map of the atlas but `skip_map`.
  bool relocalize(Frame& frame, int& matches, int skip_map = -1) DEPOT_REQUIRES(map_.mutex());
  // While the active map is young (fewer than young_map_keyframes), a
  // tracked frame that also relocalises in an older map merges the young
  // map into it (the frame's two poses give the transform); a camera lost
  // for a moment so rejoins the map it left.
  void rejoin_older_map(Frame& frame) DEPOT_REQUIRES(map_.mutex());
  bool track_local_map(Frame& frame, int& inliers, int& n_local) DEPOT_REQUIRES(map_.mutex());
  void update_local_map(Frame& frame) DEPOT_REQUIRES(map_.mutex());
  bool need_keyframe(const Frame& frame, int inliers) const DEPOT_REQUIRES(map_.mutex());
  void create_keyframe(Frame& frame) DEPOT_REQUIRES(map_.mutex());
  int discard_outliers(Frame& frame) DEPOT_REQUIRES(map_.mutex());
  int timed_optimize(Frame& frame) DEPOT_REQUIRES(map_.mutex());

  TrackingStats* current_stats_ = nullptr;
  Map& map_;
  KeyFrameSink& mapper_;
  TrackerParams params_;
  KeyFrameDatabase* places_;
  TrackingState state_ = TrackingState::kNotInitialized;
  bool reset_wanted_ = false;
  int lost_in_a_row_ = 0;  // frames lost since the last tracked one
  bool localisation_only_ = false;
  // Set by relocalise_in_map(): until a frame relocalises in the given map,
  // no new map is started (poses are wanted in that map's frame).
  bool must_relocalise_ = false;
  int rejoined_ = 0;
  Frame last_;
  Pose last_T_cr_ = Pose::Identity();  // last frame relative to its reference keyframe
  Pose velocity_ = Pose::Identity();
  bool has_velocity_ = false;
  KeyFrame* reference_ = nullptr;
  long last_keyframe_frame_ = 0;
  long last_reloc_frame_ = -1000;
  std::vector<KeyFrame*> local_keyframes_;
  std::vector<MapPoint*> local_points_;
  std::vector<TrajectoryEntry> trajectory_;
};

}  // namespace depot::slam
