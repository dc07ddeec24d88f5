#include "slam/data/map_point.h"

#include <algorithm>
#include <cmath>

#include "slam/data/keyframe.h"
#include "slam/feature/descriptor_distance.h"

namespace depot::slam {

MapPoint::MapPoint(long id_, const Eigen::Vector3d& p, KeyFrame* ref)
    : id(id_), position(p), reference(ref), first_keyframe_id(ref ? ref->id : -1) {}

void MapPoint::add_observation(KeyFrame* kf, size_t index) {
  observations[kf] = index;
}

void MapPoint::erase_observation(KeyFrame* kf) {
  if (!observations.erase(kf)) return;
  if (reference == kf && !observations.empty()) reference = observations.begin()->first;
  if (observations.size() <= 1) set_bad();
}

void MapPoint::set_bad() {
  bad = true;
  auto obs = observations;
  observations.clear();
  for (auto& [kf, idx] : obs) kf->erase_map_point(idx);
}

void MapPoint::replace(MapPoint* other) {
  if (other == this) return;
  auto obs = observations;
  observations.clear();
  bad = true;
  replaced_by = other;
  for (auto& [kf, idx] : obs) {
    if (!other->observations.count(kf)) {
      kf->add_map_point(other, idx);
      other->add_observation(kf, idx);
    } else {
      kf->erase_map_point(idx);
    }
  }
  other->found += found;
  other->visible += visible;
  other->update_descriptor();
}

MapPoint* follow_replacements(MapPoint* mp) {
  while (mp && mp->bad) mp = mp->replaced_by;
  return mp;
}

void MapPoint::update_descriptor() {
  std::vector<cv::Mat> descs;
  for (auto& [kf, idx] : observations)
    if (!kf->bad) descs.push_back(kf->features.descriptors.row(static_cast<int>(idx)));
  if (descs.empty()) return;
  const size_t n = descs.size();
  std::vector<std::vector<int>> dist(n, std::vector<int>(n, 0));
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j)
      dist[i][j] = dist[j][i] = descriptor_distance(descs[i], descs[j]);
  int best = INT32_MAX;
  size_t best_i = 0;
  for (size_t i = 0; i < n; ++i) {
    std::vector<int> d = dist[i];
    std::nth_element(d.begin(), d.begin() + (n - 1) / 2, d.end());
    if (d[(n - 1) / 2] < best) best = d[(n - 1) / 2], best_i = i;
  }
  descriptor = descs[best_i].clone();
}

void MapPoint::update_normal_and_depth() {
  if (observations.empty() || !reference) return;
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  int count = 0;
  for (auto& [kf, idx] : observations) {
    n += (position - kf->camera_center()).normalized();
    ++count;
  }
  normal = n / count;
  auto it = observations.find(reference);
  if (it == observations.end()) return;
  const float dist = static_cast<float>((position - reference->camera_center()).norm());
  const auto& kp = reference->features.keypoints[it->second];
  const ScaleLevels& lv = *reference->features.levels;
  const float level_factor = lv.scale[kp.octave];
  max_distance = dist * level_factor;
  min_distance = max_distance / lv.scale[lv.n_levels - 1];
}

int MapPoint::predict_level(float distance, const ScaleLevels& levels) const {
  const float ratio = max_distance / std::max(distance, 1e-6f);
  int level = static_cast<int>(std::ceil(std::log(ratio) / levels.log_scale_factor));
  return std::clamp(level, 0, levels.n_levels - 1);
}

}  // namespace depot::slam
