#include "slam/data/keyframe.h"

#include <algorithm>

#include "slam/data/map_point.h"

namespace depot::slam {

KeyFrame::KeyFrame(long id_, const Frame& f)
    : id(id_),
      frame_id(f.id),
      timestamp(f.timestamp),
      features(f.features),
      bow(f.bow),
      bow_features(f.bow_features),
      map_points(f.map_points),
      T_cw(f.T_cw) {}

void KeyFrame::erase_map_point(MapPoint* mp) {
  for (auto& p : map_points)
    if (p == mp) p = nullptr;
}

int KeyFrame::tracked_map_points(int min_obs) const {
  int n = 0;
  for (MapPoint* mp : map_points)
    if (mp && !mp->bad && (min_obs <= 0 || mp->n_observations() >= min_obs)) ++n;
  return n;
}

void KeyFrame::add_connection(KeyFrame* kf, int weight) {
  auto it = connections_.find(kf);
  if (it != connections_.end() && it->second == weight) return;
  connections_[kf] = weight;
  sort_connections();
}

void KeyFrame::erase_connection(KeyFrame* kf) {
  if (connections_.erase(kf)) sort_connections();
}

void KeyFrame::sort_connections() {
  std::vector<std::pair<int, KeyFrame*>> pairs;
  for (auto& [kf, w] : connections_) pairs.emplace_back(w, kf);
  std::sort(pairs.begin(), pairs.end(), [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first > b.first : a.second->id < b.second->id;
  });
  ordered_.clear();
  ordered_weights_.clear();
  for (auto& [w, kf] : pairs) ordered_.push_back(kf), ordered_weights_.push_back(w);
}

void KeyFrame::update_connections() {
  std::map<KeyFrame*, int, ById> counter;
  for (MapPoint* mp : map_points) {
    if (!mp || mp->bad) continue;
    for (auto& [kf, idx] : mp->observations)
      if (kf != this && !kf->bad) counter[kf]++;
  }
  if (counter.empty()) return;
  int best = 0;
  KeyFrame* best_kf = nullptr;
  std::map<KeyFrame*, int, ById> kept;
  for (auto& [kf, w] : counter) {
    if (w > best || (w == best && best_kf && kf->id < best_kf->id)) best = w, best_kf = kf;
    if (w >= 15) kept[kf] = w;
  }
  if (kept.empty()) kept[best_kf] = best;
  for (auto& [kf, w] : kept) kf->add_connection(this, w);
  connections_ = kept;
  sort_connections();
  if (first_connection_ && id != 0) {
    parent_ = ordered_.front();
    parent_->children_.insert(this);
    first_connection_ = false;
  }
}

std::vector<KeyFrame*> KeyFrame::covisibles(size_t n) const {
  std::vector<KeyFrame*> out;
  for (KeyFrame* kf : ordered_) {
    if (out.size() >= n) break;
    if (!kf->bad) out.push_back(kf);
  }
  return out;
}

std::vector<KeyFrame*> KeyFrame::covisibles_with_weight(int min_weight) const {
  std::vector<KeyFrame*> out;
  for (size_t i = 0; i < ordered_.size() && ordered_weights_[i] >= min_weight; ++i)
    if (!ordered_[i]->bad) out.push_back(ordered_[i]);
  return out;
}

int KeyFrame::weight(KeyFrame* kf) const {
  auto it = connections_.find(kf);
  return it == connections_.end() ? 0 : it->second;
}

void KeyFrame::set_parent(KeyFrame* p) {
  if (parent_) parent_->children_.erase(this);
  parent_ = p;
  if (p) p->children_.insert(this);
  first_connection_ = false;
}

void KeyFrame::set_bad() {
  if (map_origin || !loop_edges.empty()) return;
  for (auto& [kf, w] : connections_) kf->erase_connection(this);
  for (size_t i = 0; i < map_points.size(); ++i)
    if (map_points[i]) map_points[i]->erase_observation(this);
  connections_.clear();
  ordered_.clear();
  ordered_weights_.clear();
  // Children move to this keyframe's parent (a simple, valid spanning tree;
  // ORB-SLAM2 picks the most covisible candidate, which loop closing may want).
  for (KeyFrame* child : children_) {
    child->parent_ = parent_;
    if (parent_) parent_->children_.insert(child);
  }
  if (parent_) {
    parent_->children_.erase(this);
    T_cp = T_cw * parent_->T_cw.inverse();
  }
  children_.clear();
  bad = true;
}

}  // namespace depot::slam
