#pragma once
// A 3-D landmark: its position, the keyframes that observe it, a
// representative descriptor and the distance range it can be matched at.
#include <map>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "slam/data/by_id.h"
#include "slam/data/scale_levels.h"

namespace depot::slam {

class KeyFrame;

class MapPoint {
 public:
  MapPoint(long id, const Eigen::Vector3d& position, KeyFrame* reference);

  long id;
  Eigen::Vector3d position;
  cv::Mat descriptor;               // 1 x 32, the most representative
  Eigen::Vector3d normal{0, 0, 1};  // mean viewing direction
  float min_distance = 0, max_distance = 0;
  std::map<KeyFrame*, size_t, ById> observations;  // keyframe -> keypoint index
  KeyFrame* reference;
  long first_keyframe_id;
  int map_id = 0;              // the atlas map of its reference keyframe (Map)
  int visible = 1, found = 1;  // tracking statistics
  bool bad = false;
  // Set when fusion merged this point into another (it is bad then); holders
  // of MapPoint* outside keyframes follow it (follow_replacements).
  MapPoint* replaced_by = nullptr;
  long last_seen_frame = -1;  // bookkeeping for local-map search
  long local_map_for = -1;    // frame whose local map already holds the point
  long fuse_candidate_for = -1;
  long local_ba_for = -1;
  // Loop correction: the keyframe whose correction moved the point, and the
  // one it moved with (its pose change then moves the point again).
  long loop_corrected_for = -1;
  KeyFrame* loop_reference = nullptr;

  void add_observation(KeyFrame* kf, size_t index);
  // Removes an observation; the point turns bad when fewer than 2 remain.
  void erase_observation(KeyFrame* kf);
  int n_observations() const { return static_cast<int>(observations.size()); }
  float found_ratio() const { return static_cast<float>(found) / visible; }
  // The descriptor with the least median distance to all observations.
  void update_descriptor();
  // Viewing direction and the scale-invariance distance range.
  void update_normal_and_depth();
  int predict_level(float distance, const ScaleLevels& levels) const;
  // Marks the point bad and detaches it from all keyframes.
  void set_bad();
  // Transfers this point's observations to `other` and marks itself bad.
  void replace(MapPoint* other);
};

// The point that now stands for `mp`: `mp` itself while it is good, else the
// end of its replaced_by chain (a point fused twice names its first survivor,
// which names the second), or nullptr when the chain ends in a point culled
// for good. Chains cannot cycle: only good points are fused, and a fused
// point never turns good again. Caller holds the map lock.
MapPoint* follow_replacements(MapPoint* mp);

}  // namespace depot::slam
