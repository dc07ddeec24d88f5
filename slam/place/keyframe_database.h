#pragma once
// The map's keyframes indexed by word (an inverted index), to find the
// keyframes that look like an image: candidates for relocalisation and for
// loop closing, scored as ORB-SLAM2 does (shared words, then bag-of-words
// similarity, then accumulated over covisible groups).
//
// Locking: the index has its own mutex (local mapping adds and erases while
// tracking and loop closing query). The queries read keyframes' covisibility,
// so their callers hold the map mutex. A keyframe's bag of words is written
// before add() and never changed after.
#include <memory>
#include <unordered_map>
#include <vector>

#include "common/mutex.h"
#include "slam/data/keyframe.h"
#include "slam/place/vocabulary.h"

namespace depot::slam {

class KeyFrameDatabase {
 public:
  explicit KeyFrameDatabase(std::shared_ptr<const Vocabulary> vocabulary);

  const Vocabulary& vocabulary() const { return *vocabulary_; }
  // Computes the keyframe's bag of words and direct index when missing.
  void describe(KeyFrame& kf) const;
  void describe(Frame& frame) const;

  void add(KeyFrame* kf);
  void erase(KeyFrame* kf);
  void clear();
  size_t size() const;

  // Keyframes that may show what `frame` shows, best first: those sharing at
  // least 80 % of the most words any keyframe shares with it, grouped with
  // their ten best covisibles; groups scoring at least 75 % of the best
  // group give their best keyframe. Describes the frame if needed.
  // Keyframes of the atlas map `skip_map` (map.h) are left out, before the
  // shares above are taken.
  std::vector<KeyFrame*> relocalisation_candidates(Frame& frame, int skip_map = -1) const;

  // Keyframes that may close a loop with `kf`: as above, but only those not
  // connected to kf in the covisibility graph, and scoring at least
  // `min_score` (ORB-SLAM2 uses the lowest score of kf's covisibles).
  std::vector<KeyFrame*> loop_candidates(const KeyFrame& kf, double min_score) const;

 private:
  struct Scored {
    KeyFrame* kf;
    double score;
  };
  std::vector<KeyFrame*> candidates(const BowVector& bow, const KeyFrame* query, double min_score,
                                    int skip_map = -1) const;

  std::shared_ptr<const Vocabulary> vocabulary_;
  mutable Mutex mutex_;
  std::unordered_map<WordId, std::vector<KeyFrame*>> index_ DEPOT_GUARDED_BY(mutex_);
  size_t n_keyframes_ DEPOT_GUARDED_BY(mutex_) = 0;
};

}  // namespace depot::slam
