#include "slam/data/map.h"

namespace depot::slam {

KeyFrame* Map::create_keyframe(const Frame& frame) {
  kf_storage_.push_back(std::make_unique<KeyFrame>(static_cast<long>(kf_storage_.size()), frame));
  KeyFrame* kf = kf_storage_.back().get();
  keyframes_.insert(kf);
  return kf;
}

MapPoint* Map::create_map_point(const Eigen::Vector3d& position, KeyFrame* reference) {
  mp_storage_.push_back(
      std::make_unique<MapPoint>(static_cast<long>(mp_storage_.size()), position, reference));
  MapPoint* mp = mp_storage_.back().get();
  map_points_.insert(mp);
  return mp;
}

void Map::clear() {
  for (MapPoint* mp : map_points_) mp->bad = true;
  for (KeyFrame* kf : keyframes_) kf->bad = true;
  map_points_.clear();
  keyframes_.clear();
}

}  // namespace depot::slam
