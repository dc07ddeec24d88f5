#pragma once
// A keyframe: a frame kept in the map, with its covisibility connections
// (keyframes sharing map points, weighted by how many) and spanning tree.
#include <map>
#include <set>
#include <vector>

#include "common/pose.h"
#include "slam/data/by_id.h"
#include "slam/data/features.h"
#include "slam/data/frame.h"
#include "slam/data/bow_vector.h"

namespace depot::slam {

class MapPoint;

class KeyFrame {
 public:
  KeyFrame(long id, const Frame& frame);

  long id;
  long frame_id;
  double timestamp;
  Features features;
  // Bag of words and direct index (KeyFrameDatabase::describe), set by
  // local mapping before the keyframe enters the database; fixed after.
  BowVector bow;
  FeatureVector bow_features;
  std::vector<MapPoint*> map_points;
  Pose T_cw;
  Pose T_cp = Pose::Identity();  // relative to the parent, fixed when set bad
  bool bad = false;
  // The map of the atlas it belongs to (Map::active_map() when made; a
  // merge moves it to the map it joins), and whether it started that map:
  // an origin is fixed in bundle adjustment and never culled.
  int map_id = 0;
  bool map_origin = false;
  // Keyframes this one closed a loop with (loop closing); such keyframes are
  // never culled, so the essential graph keeps the loop.
  std::set<KeyFrame*, ById> loop_edges;
  // Markers that avoid sets in hot loops: the id of the keyframe/frame whose
  // processing last visited this keyframe.
  long local_ba_for = -1, fixed_ba_for = -1, track_local_for = -1, fuse_target_for = -1;

  Eigen::Vector3d camera_center() const { return T_cw.inverse().translation(); }
  void add_map_point(MapPoint* mp, size_t index) { map_points[index] = mp; }
  void erase_map_point(size_t index) { map_points[index] = nullptr; }
  void erase_map_point(MapPoint* mp);
  // Map points that are set and not bad; `min_obs` > 0 requires that many observers.
  int tracked_map_points(int min_obs) const;

  // Covisibility: recomputed from the shared map points (weight >= 15, or the
  // best one), updating the neighbours' links and the spanning tree.
  void update_connections();
  void add_connection(KeyFrame* kf, int weight);
  void erase_connection(KeyFrame* kf);
  std::vector<KeyFrame*> covisibles(size_t n = SIZE_MAX) const;
  std::vector<KeyFrame*> covisibles_with_weight(int min_weight) const;
  int weight(KeyFrame* kf) const;
  KeyFrame* parent() const { return parent_; }
  // Restores a spanning-tree link (a loaded map): `p` becomes the parent.
  void set_parent(KeyFrame* p);
  const std::set<KeyFrame*, ById>& children() const { return children_; }
  // Removes the keyframe from the graph (not the first one).
  void set_bad();

 private:
  void sort_connections();
  std::map<KeyFrame*, int, ById> connections_;
  std::vector<KeyFrame*> ordered_;
  std::vector<int> ordered_weights_;
  KeyFrame* parent_ = nullptr;
  std::set<KeyFrame*, ById> children_;
  bool first_connection_ = true;
};

}  // namespace depot::slam
