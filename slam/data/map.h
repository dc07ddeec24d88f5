#pragma once
// The map: owns keyframes and map points (never freed while the map lives;
// bad ones leave the active sets), with one mutex that tracking and local
// mapping hold while they read or change it.
//
// Locking rule: mutex() guards the Map's sets and every field of every
// KeyFrame and MapPoint it owns (poses, positions, observations,
// covisibility, spanning tree, bad flags). Any thread that reads or writes
// them holds it; the methods here and of KeyFrame / MapPoint do not lock
// (their callers do). Pointers stay valid without the lock (nothing is
// freed), but what they point to may not be read without it.
#include <memory>
#include <mutex>
#include <set>
#include <vector>

#include "slam/data/by_id.h"
#include "slam/data/keyframe.h"
#include "slam/data/map_point.h"

namespace depot::slam {

class Map {
 public:
  KeyFrame* create_keyframe(const Frame& frame);
  MapPoint* create_map_point(const Eigen::Vector3d& position, KeyFrame* reference);
  void erase_keyframe(KeyFrame* kf) { keyframes_.erase(kf); }
  void erase_map_point(MapPoint* mp) { map_points_.erase(mp); }

  const std::set<KeyFrame*, ById>& keyframes() const { return keyframes_; }
  const std::set<MapPoint*, ById>& map_points() const { return map_points_; }
  size_t n_keyframes() const { return keyframes_.size(); }
  size_t n_map_points() const { return map_points_.size(); }
  KeyFrame* first_keyframe() const { return keyframes_.empty() ? nullptr : *keyframes_.begin(); }

  // Forgets every keyframe and point (they turn bad; memory stays, so old
  // pointers remain valid). Used when tracking is lost right after start.
  void clear();

  std::mutex& mutex() { return mutex_; }
  // All keyframes ever created (for the trajectory, bad ones included).
  const std::vector<std::unique_ptr<KeyFrame>>& all_keyframes() const { return kf_storage_; }
  size_t allocated_map_points() const { return mp_storage_.size(); }

 private:
  std::mutex mutex_;
  std::vector<std::unique_ptr<KeyFrame>> kf_storage_;
  std::vector<std::unique_ptr<MapPoint>> mp_storage_;
  std::set<KeyFrame*, ById> keyframes_;
  std::set<MapPoint*, ById> map_points_;
};

}  // namespace depot::slam
