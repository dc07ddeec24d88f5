#include "slam/data/map.h"

#include <algorithm>
#include <map>

namespace depot::slam {

KeyFrame* Map::create_keyframe(const Frame& frame) {
  kf_storage_.push_back(std::make_unique<KeyFrame>(static_cast<long>(kf_storage_.size()), frame));
  KeyFrame* kf = kf_storage_.back().get();
  kf->map_id = active_;
  kf->map_origin = n_keyframes_in(active_) == 0;
  keyframes_.insert(kf);
  return kf;
}

MapPoint* Map::create_map_point(const Eigen::Vector3d& position, KeyFrame* reference) {
  mp_storage_.push_back(
      std::make_unique<MapPoint>(static_cast<long>(mp_storage_.size()), position, reference));
  MapPoint* mp = mp_storage_.back().get();
  mp->map_id = reference ? reference->map_id : active_;
  map_points_.insert(mp);
  return mp;
}

std::vector<KeyFrame*> Map::keyframes_in(int map_id) const {
  std::vector<KeyFrame*> out;
  for (KeyFrame* kf : keyframes_)
    if (kf->map_id == map_id) out.push_back(kf);
  return out;
}

size_t Map::n_keyframes_in(int map_id) const {
  return static_cast<size_t>(
      std::count_if(keyframes_.begin(), keyframes_.end(),
                    [&](const KeyFrame* kf) { return kf->map_id == map_id; }));
}

KeyFrame* Map::first_keyframe_in(int map_id) const {
  for (KeyFrame* kf : keyframes_)
    if (kf->map_id == map_id) return kf;
  return nullptr;
}

std::vector<int> Map::map_ids() const {
  std::vector<int> ids;
  for (const KeyFrame* kf : keyframes_)
    if (std::find(ids.begin(), ids.end(), kf->map_id) == ids.end()) ids.push_back(kf->map_id);
  return ids;
}

void Map::merge_maps(int from, int into, const Pose& T_into_from) {
  const Pose T_from_into = T_into_from.inverse();
  // Every keyframe ever made of `from`, bad ones too: frames still hang off
  // culled keyframes through their parents (the trajectory follows them).
  for (const std::unique_ptr<KeyFrame>& kf : kf_storage_) {
    if (kf->map_id != from) continue;
    kf->T_cw = kf->T_cw * T_from_into;
    kf->map_id = into;
    kf->map_origin = false;
  }
  for (const std::unique_ptr<MapPoint>& mp : mp_storage_) {
    if (mp->map_id != from) continue;
    mp->position = T_into_from * mp->position;
    mp->map_id = into;
    if (!mp->bad) mp->update_normal_and_depth();
  }
  if (active_ == from) active_ = into;
}

void Map::clear() {
  for (MapPoint* mp : map_points_) mp->bad = true;
  for (KeyFrame* kf : keyframes_) kf->bad = true;
  map_points_.clear();
  keyframes_.clear();
}

void Map::restore_atlas() {
  std::map<int, size_t> keyframes;
  for (const KeyFrame* kf : keyframes_) ++keyframes[kf->map_id];
  next_map_ = keyframes.empty() ? 1 : keyframes.rbegin()->first + 1;
  active_ = 0;
  size_t most = 0;
  for (const auto& [id, n] : keyframes)
    if (n > most) active_ = id, most = n;
}

std::vector<KeyFrame*> Map::discard_map(int map_id) {
  std::vector<KeyFrame*> discarded = keyframes_in(map_id);
  for (KeyFrame* kf : discarded) {
    kf->bad = true;
    keyframes_.erase(kf);
  }
  for (auto it = map_points_.begin(); it != map_points_.end();) {
    if ((*it)->map_id != map_id) {
      ++it;
      continue;
    }
    (*it)->bad = true;
    it = map_points_.erase(it);
  }
  return discarded;
}

}  // namespace depot::slam
