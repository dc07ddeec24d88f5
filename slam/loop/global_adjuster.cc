#include "slam/loop/global_adjuster.h"

#include <deque>
#include <unordered_map>
#include <unordered_set>

#include "slam/data/map_point.h"
#include "slam/mapping/local_mapper.h"
#include "slam/optimize/optimizer.h"

namespace depot::slam {
void apply_global_adjustment(Map& map, const GlobalBaResult& result) {
  std::unordered_map<KeyFrame*, Pose> before, after;
  for (const auto& [k, T_cw] : result.keyframes) {
    if (k->bad) continue;
    before[k] = k->T_cw;
    after[k] = T_cw;
  }
  // Keyframes made while it solved: down the spanning trees from their
  // roots (a map's origin, or the old origin of a map merged into another),
  // each keeps its pose relative to its parent.
  std::deque<KeyFrame*> todo;
  std::unordered_set<const KeyFrame*> seen;
  for (KeyFrame* k : map.keyframes())
    if (!k->parent()) {
      todo.push_back(k);
      seen.insert(k);
    }
  while (!todo.empty()) {
    KeyFrame* parent = todo.front();
    todo.pop_front();
    for (KeyFrame* child : parent->children()) {
      if (!seen.insert(child).second) continue;
      todo.push_back(child);
      if (child->bad || after.count(child) || !after.count(parent)) continue;
      before[child] = child->T_cw;
      after[child] = child->T_cw * before[parent].inverse() * after[parent];
    }
  }
  for (const auto& [k, T_cw] : after) k->T_cw = T_cw;

  std::unordered_set<const MapPoint*> solved;
  for (const auto& [mp, x] : result.points) {
    if (mp->bad) continue;
    mp->position = x;
    solved.insert(mp);
  }
  // Points made while it solved move with their reference keyframe.
  for (MapPoint* mp : map.map_points()) {
    if (mp->bad) continue;
    if (!solved.count(mp)) {
      const auto b = before.find(mp->reference);
      if (b == before.end()) continue;
      mp->position = after[mp->reference].inverse() * (b->second * mp->position);
    }
    mp->update_normal_and_depth();
  }
}

GlobalAdjuster::GlobalAdjuster(Map& map, LocalMapper& mapper, bool threaded, int iterations)
    : map_(map), mapper_(mapper), threaded_(threaded), iterations_(iterations) {}

GlobalAdjuster::~GlobalAdjuster() {
  abort();
}

void GlobalAdjuster::start() {
  abort();
  abort_ = false;
  if (!threaded_) {
    run();
    return;
  }
  MutexLock lock(mutex_);
  running_ = true;
  thread_ = std::thread([this] { run(); });
}

void GlobalAdjuster::abort() {
  abort_ = true;
  wait();
}

void GlobalAdjuster::wait() {
  std::thread finished;
  {
    MutexLock lock(mutex_);
    finished = std::move(thread_);
  }
  if (finished.joinable()) finished.join();
}

bool GlobalAdjuster::running() const {
  MutexLock lock(mutex_);
  return running_;
}

int GlobalAdjuster::completed() const {
  MutexLock lock(mutex_);
  return completed_;
}

std::exception_ptr GlobalAdjuster::failure() const {
  MutexLock lock(mutex_);
  return failure_;
}

void GlobalAdjuster::run() {
  bool applied = false;
  try {
    const GlobalBaResult result = global_bundle_adjustment(map_, &abort_, iterations_);
    if (result.completed && !abort_) {
      const MappingPause paused(mapper_);  // resumed after the map lock is released
      MutexLock lock(map_.mutex());
      apply_global_adjustment(map_, result);
      applied = true;
    }
  } catch (...) {
    MutexLock lock(mutex_);
    if (!failure_) failure_ = std::current_exception();
  }
  MutexLock lock(mutex_);
  completed_ += applied;
  running_ = false;
}

}  // namespace depot::slam
