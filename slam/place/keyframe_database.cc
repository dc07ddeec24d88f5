#include "slam/place/keyframe_database.h"

#include <algorithm>
#include <set>

namespace depot::slam {

KeyFrameDatabase::KeyFrameDatabase(std::shared_ptr<const Vocabulary> vocabulary)
    : vocabulary_(std::move(vocabulary)) {}

void KeyFrameDatabase::describe(KeyFrame& kf) const {
  if (kf.bow.empty()) vocabulary_->transform(kf.features.descriptors, kf.bow, kf.bow_features);
}

void KeyFrameDatabase::describe(Frame& frame) const {
  if (frame.bow.empty())
    vocabulary_->transform(frame.features.descriptors, frame.bow, frame.bow_features);
}

void KeyFrameDatabase::add(KeyFrame* kf) {
  MutexLock lock(mutex_);
  for (const auto& [word, weight] : kf->bow) index_[word].push_back(kf);
  ++n_keyframes_;
}

void KeyFrameDatabase::erase(KeyFrame* kf) {
  MutexLock lock(mutex_);
  bool found = false;
  for (const auto& [word, weight] : kf->bow) {
    auto it = index_.find(word);
    if (it == index_.end()) continue;
    auto& list = it->second;
    auto pos = std::find(list.begin(), list.end(), kf);
    if (pos != list.end()) list.erase(pos), found = true;
  }
  if (found) --n_keyframes_;
}

void KeyFrameDatabase::clear() {
  MutexLock lock(mutex_);
  index_.clear();
  n_keyframes_ = 0;
}

size_t KeyFrameDatabase::size() const {
  MutexLock lock(mutex_);
  return n_keyframes_;
}

std::vector<KeyFrame*> KeyFrameDatabase::relocalisation_candidates(Frame& frame,
                                                                   int skip_map) const {
  describe(frame);
  return candidates(frame.bow, nullptr, 0, skip_map);
}

std::vector<KeyFrame*> KeyFrameDatabase::loop_candidates(const KeyFrame& kf,
                                                         double min_score) const {
  return candidates(kf.bow, &kf, min_score);
}

std::vector<KeyFrame*> KeyFrameDatabase::candidates(const BowVector& bow, const KeyFrame* query,
                                                    double min_score, int skip_map) const {
  // Keyframes sharing words with the query, and how many.
  std::unordered_map<KeyFrame*, int> shared;
  {
    MutexLock lock(mutex_);
    for (const auto& [word, weight] : bow) {
      auto it = index_.find(word);
      if (it == index_.end()) continue;
      for (KeyFrame* kf : it->second) shared[kf]++;
    }
  }
  std::set<const KeyFrame*> connected;
  for (const auto& [kf, n] : shared)
    if (kf->map_id == skip_map) connected.insert(kf);
  if (query) {
    connected.insert(query);
    for (KeyFrame* c : query->covisibles()) connected.insert(c);
  }
  int most = 0;
  for (const auto& [kf, n] : shared)
    if (!kf->bad && !connected.count(kf)) most = std::max(most, n);
  if (most == 0) return {};
  const int min_shared = static_cast<int>(0.8 * most);

  std::unordered_map<const KeyFrame*, double> score;
  for (const auto& [kf, n] : shared) {
    if (kf->bad || connected.count(kf) || n <= min_shared) continue;
    const double s = bow_similarity(bow, kf->bow);
    if (s >= min_score) score[kf] = s;
  }
  if (score.empty()) return {};

  // Accumulate over each candidate's ten best covisibles that are candidates
  // too; the group is represented by its best keyframe.
  std::vector<Scored> groups;
  double best_group = 0;
  for (const auto& [kf, s] : score) {
    double total = s;
    const KeyFrame* best = kf;
    double best_score = s;
    for (KeyFrame* c : kf->covisibles(10)) {
      auto it = score.find(c);
      if (it == score.end()) continue;
      total += it->second;
      if (it->second > best_score) best = c, best_score = it->second;
    }
    groups.push_back({const_cast<KeyFrame*>(best), total});
    best_group = std::max(best_group, total);
  }
  std::sort(groups.begin(), groups.end(), [](const Scored& a, const Scored& b) {
    return a.score != b.score ? a.score > b.score : a.kf->id < b.kf->id;
  });
  std::vector<KeyFrame*> out;
  std::set<const KeyFrame*> taken;
  for (const Scored& g : groups) {
    if (g.score < 0.75 * best_group) break;
    if (taken.insert(g.kf).second) out.push_back(g.kf);
  }
  return out;
}

}  // namespace depot::slam
