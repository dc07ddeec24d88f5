#pragma once
// The map: owns keyframes and map points (never freed while the map lives;
// bad ones leave the active sets), with one mutex that tracking and local
// mapping hold while they read or change it.
//
// It is an atlas (ORB-SLAM3): it may hold several maps, each a set of
// keyframes and points in a coordinate frame of its own, named by the
// map_id every keyframe and point carries. One map is active: tracking
// adds to it, and a lost camera that cannot relocalise starts a new one
// (begin_map) instead of throwing the old one away. Relocalisation searches
// every map; loop closing merges two maps when it finds a place both have
// seen (merge_maps moves one into the other's frame). Nothing links
// keyframes or points of different maps.
//
// Locking rule: mutex() guards the Map's sets and every field of every
// KeyFrame and MapPoint it owns (poses, positions, observations,
// covisibility, spanning tree, bad flags, map ids) and the active map.
// Any thread that reads or writes them holds it; the methods here and of
// KeyFrame / MapPoint do not lock (their callers do). The Map's own members
// and methods carry clang thread-safety annotations (common/mutex.h), so a
// clang build refuses a call without the lock; KeyFrame and MapPoint fields
// cannot name their map's lock and rely on this rule. Pointers stay valid
// without the lock (nothing is freed), but what they point to may not be
// read without it.
#include <memory>
#include <set>
#include <vector>

#include "common/mutex.h"
#include "common/pose.h"
#include "slam/data/by_id.h"
#include "slam/data/keyframe.h"
#include "slam/data/map_point.h"

namespace depot::slam {

class Map {
 public:
  // A keyframe of the active map (its origin when it is the map's first).
  KeyFrame* create_keyframe(const Frame& frame) DEPOT_REQUIRES(mutex_);
  // A point of its reference keyframe's map (the active one without reference).
  MapPoint* create_map_point(const Eigen::Vector3d& position, KeyFrame* reference)
      DEPOT_REQUIRES(mutex_);
  void erase_keyframe(KeyFrame* kf) DEPOT_REQUIRES(mutex_) { keyframes_.erase(kf); }
  void erase_map_point(MapPoint* mp) DEPOT_REQUIRES(mutex_) { map_points_.erase(mp); }

  // Every map's keyframes and points.
  const std::set<KeyFrame*, ById>& keyframes() const DEPOT_REQUIRES(mutex_) { return keyframes_; }
  const std::set<MapPoint*, ById>& map_points() const DEPOT_REQUIRES(mutex_) { return map_points_; }
  size_t n_keyframes() const DEPOT_REQUIRES(mutex_) { return keyframes_.size(); }
  size_t n_map_points() const DEPOT_REQUIRES(mutex_) { return map_points_.size(); }
  KeyFrame* first_keyframe() const DEPOT_REQUIRES(mutex_) {
    return keyframes_.empty() ? nullptr : *keyframes_.begin();
  }

  // One map of the atlas.
  std::vector<KeyFrame*> keyframes_in(int map_id) const DEPOT_REQUIRES(mutex_);
  size_t n_keyframes_in(int map_id) const DEPOT_REQUIRES(mutex_);
  // Its oldest keyframe that is still in it, or null when it has none.
  KeyFrame* first_keyframe_in(int map_id) const DEPOT_REQUIRES(mutex_);
  // Ids of the maps that have keyframes, oldest first.
  std::vector<int> map_ids() const DEPOT_REQUIRES(mutex_);

  int active_map() const DEPOT_REQUIRES(mutex_) { return active_; }
  // Makes a map the active one (relocalisation found the camera in it).
  void activate(int map_id) DEPOT_REQUIRES(mutex_) { active_ = map_id; }
  // A new, empty map becomes the active one; the others are kept. Returns its id.
  int begin_map() DEPOT_REQUIRES(mutex_) { return active_ = next_map_++; }
  // Moves every keyframe and point of map `from` into map `into`: T_into_from
  // takes `from`'s world coordinates to `into`'s. `from`'s origin stops being
  // one. The active map follows when it was `from`.
  void merge_maps(int from, int into, const Pose& T_into_from) DEPOT_REQUIRES(mutex_);

  // After a saved atlas was loaded keyframe by keyframe: new maps get ids
  // above every loaded one, and the map with most keyframes is active.
  void restore_atlas() DEPOT_REQUIRES(mutex_);

  // Forgets every keyframe and point (they turn bad; memory stays, so old
  // pointers remain valid). Used when tracking is lost right after start.
  void clear() DEPOT_REQUIRES(mutex_);
  // Forgets one map's keyframes and points the same way (a young map lost
  // right after its start); the others stay. Returns its keyframes.
  std::vector<KeyFrame*> discard_map(int map_id) DEPOT_REQUIRES(mutex_);

  // const: a reader holding a const Map& still locks it.
  Mutex& mutex() const DEPOT_RETURN_CAPABILITY(mutex_) { return mutex_; }
  // All keyframes ever created (for the trajectory, bad ones included).
  const std::vector<std::unique_ptr<KeyFrame>>& all_keyframes() const DEPOT_REQUIRES(mutex_) {
    return kf_storage_;
  }
  size_t allocated_map_points() const DEPOT_REQUIRES(mutex_) { return mp_storage_.size(); }

 private:
  mutable Mutex mutex_;
  std::vector<std::unique_ptr<KeyFrame>> kf_storage_ DEPOT_GUARDED_BY(mutex_);
  std::vector<std::unique_ptr<MapPoint>> mp_storage_ DEPOT_GUARDED_BY(mutex_);
  std::set<KeyFrame*, ById> keyframes_ DEPOT_GUARDED_BY(mutex_);
  std::set<MapPoint*, ById> map_points_ DEPOT_GUARDED_BY(mutex_);
  int active_ DEPOT_GUARDED_BY(mutex_) = 0;
  int next_map_ DEPOT_GUARDED_BY(mutex_) = 1;
};

}  // namespace depot::slam
