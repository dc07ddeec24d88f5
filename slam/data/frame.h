#pragma once
// One tracked image: its features, the map points matched to them and the
// estimated pose T_cw (world -> camera).
#include <vector>

#include "common/pose.h"
#include "slam/data/features.h"
#include "slam/data/bow_vector.h"

namespace depot::slam {

class MapPoint;
class KeyFrame;

struct Frame {
  long id = 0;
  double timestamp = 0;
  Features features;
  BowVector bow;  // empty until needed (relocalisation)
  FeatureVector bow_features;
  std::vector<MapPoint*> map_points;  // per keypoint, nullptr when unmatched
  std::vector<bool> outlier;          // per keypoint, set by pose optimisation
  Pose T_cw = Pose::Identity();
  bool has_pose = false;
  KeyFrame* reference = nullptr;

  Frame() = default;
  Frame(long id_, double t, Features f) : id(id_), timestamp(t), features(std::move(f)) {
    map_points.assign(features.size(), nullptr);
    outlier.assign(features.size(), false);
  }
  Eigen::Vector3d camera_center() const { return T_cw.inverse().translation(); }
  size_t size() const { return features.size(); }
};

}  // namespace depot::slam
