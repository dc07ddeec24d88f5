#include "slam/track/tracker.h"

#include <algorithm>
#include <chrono>
#include <map>

#include "slam/optimize/optimizer.h"
#include "slam/place/keyframe_database.h"
#include "slam/solve/pnp_ransac.h"

namespace depot::slam {
namespace {

// Adds the lifetime of the timer to a millisecond counter.
class ScopedTimer {
 public:
  explicit ScopedTimer(double* total) : total_(total), start_(std::chrono::steady_clock::now()) {}
  ~ScopedTimer() {
    if (total_)
      *total_ +=
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_)
              .count();
  }

 private:
  double* total_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace

Tracker::Tracker(Map& map, KeyFrameSink& mapper, const TrackerParams& params,
                 KeyFrameDatabase* places)
    : map_(map), mapper_(mapper), params_(params), places_(places) {}

TrackingState Tracker::track(Frame frame, TrackingStats* stats) {
  MutexLock lock(map_.mutex());
  TrackingStats local;
  current_stats_ = &local;
  // Local BA and loop closing move keyframes between frames: the last
  // frame's pose follows its reference keyframe (ORB-SLAM2's UpdateLastFrame).
  if (last_.has_pose && last_.reference && !last_.reference->bad)
    last_.T_cw = last_T_cr_ * last_.reference->T_cw;
  bool ok = false;
  bool relocalized = false;
  FrameState frame_state = FrameState::kNotInitialized;
  if (state_ == TrackingState::kNotInitialized) {
    ok = !localisation_only_ && initialize(frame);
    if (ok) {
      frame_state = FrameState::kNewMap;
      local.method = TrackingMethod::kInitialization;
      local.new_keyframe = true;
      local.inliers =
          static_cast<int>(std::count_if(frame.map_points.begin(), frame.map_points.end(),
                                         [](MapPoint* p) { return p != nullptr; }));
    }
  } else {
    follow_replaced_points_in_last_frame();
    if (state_ == TrackingState::kOk || state_ == TrackingState::kRelocalized) {
      if (has_velocity_ && frame.id > last_reloc_frame_ + 1) {
        local.method = TrackingMethod::kMotionModel;
        ok = track_motion_model(frame, local.matches);
      }
      if (!ok) {
        local.method = TrackingMethod::kReferenceKeyFrame;
        ok = track_reference_keyframe(frame, local.matches);
      }
    } else {
      local.method = TrackingMethod::kRelocalization;
      ok = relocalize(frame, local.matches);
      relocalized = ok;
    }
    frame.reference = reference_;
    if (ok) ok = track_local_map(frame, local.inliers, local.local_points);
    state_ = ok ? (relocalized ? TrackingState::kRelocalized : TrackingState::kOk)
                : TrackingState::kLost;
    frame_state =
        ok ? (relocalized ? FrameState::kRelocalized : FrameState::kOk) : FrameState::kLost;
    const bool lost_before = local.method == TrackingMethod::kRelocalization;
    if (!ok && lost_before && params_.atlas && !localisation_only_ && !must_relocalise_ &&
        can_initialize(frame)) {
      // Lost, and no map knows this place: a new map starts here; the old
      // ones stay for loop closing to merge.
      std::fill(frame.map_points.begin(), frame.map_points.end(), nullptr);
      std::fill(frame.outlier.begin(), frame.outlier.end(), false);
      if (map_.n_keyframes_in(map_.active_map()) > 0) map_.begin_map();
      has_velocity_ = false;
      ok = initialize(frame);
      frame_state = FrameState::kNewMap;
      local.method = TrackingMethod::kInitialization;
      local.new_keyframe = true;
      local.inliers = 0;
      for (MapPoint* p : frame.map_points) local.inliers += p != nullptr;
      lost_in_a_row_ = 0;
      trajectory_.push_back({frame.timestamp, frame.reference, Pose::Identity(), frame_state});
      reset_wanted_ = false;
      last_ = std::move(frame);
      last_T_cr_ = Pose::Identity();
      current_stats_ = nullptr;
      if (stats) *stats = local;
      return state_;
    }
    if (ok && params_.atlas && !localisation_only_ && !relocalized) rejoin_older_map(frame);
    if (ok) {
      velocity_ = frame.T_cw * last_.T_cw.inverse();
      has_velocity_ = last_.has_pose;
      if (!localisation_only_ && need_keyframe(frame, local.inliers)) {
        create_keyframe(frame);
        local.new_keyframe = true;
      }
      // Outliers must not be carried into the next frame's motion model.
      for (size_t i = 0; i < frame.size(); ++i)
        if (frame.map_points[i] && frame.outlier[i]) frame.map_points[i] = nullptr;
    } else {
      has_velocity_ = false;
      frame.has_pose = false;
    }
  }
  // A lost frame has no pose: it is recorded, but not as a pose (the
  // trajectory leaves it out).
  if (ok && frame.reference)
    trajectory_.push_back({frame.timestamp, frame.reference,
                           frame.T_cw * frame.reference->T_cw.inverse(), frame_state});
  else
    trajectory_.push_back({frame.timestamp, nullptr, Pose::Identity(), frame_state});
  lost_in_a_row_ = state_ == TrackingState::kLost ? lost_in_a_row_ + 1 : 0;
  const size_t keyframes = map_.n_keyframes_in(map_.active_map());
  // With the atlas only a map lost while tiny is reset (its frames would
  // otherwise stay behind as a weak map that relocalisation finds first);
  // a young one is left for a new map and rejoin_older_map.
  reset_wanted_ =
      !localisation_only_ && state_ == TrackingState::kLost &&
      (keyframes <= static_cast<size_t>(params_.reset_keyframes) ||
       (!params_.atlas && keyframes < static_cast<size_t>(params_.young_map_keyframes) &&
        lost_in_a_row_ >= params_.young_map_lost_frames)) &&
      !(params_.atlas && must_relocalise_);
  if (ok) {
    if (frame.reference) last_T_cr_ = frame.T_cw * frame.reference->T_cw.inverse();
    last_ = std::move(frame);
  } else
    last_.timestamp = frame.timestamp;
  current_stats_ = nullptr;
  if (stats) *stats = local;
  return state_;
}

void Tracker::relocalise_in_map() {
  reset_wanted_ = false;
  lost_in_a_row_ = 0;
  if (map_.n_keyframes() == 0) return;  // nothing to relocalise against
  state_ = TrackingState::kLost;
  must_relocalise_ = true;
  has_velocity_ = false;
  last_ = Frame();
  reference_ = nullptr;
}

void Tracker::follow_replaced_points_in_last_frame() {
  for (MapPoint*& mp : last_.map_points)
    if (mp) mp = follow_replacements(mp);
}

void Tracker::reset() {
  forget_motion();
  abandon_frames(-1);
}

void Tracker::abandon_frames(int map_id) {
  for (TrajectoryEntry& e : trajectory_) {
    if (map_id >= 0 && (!e.reference || e.reference->map_id != map_id)) continue;
    e.reference = nullptr;
    if (is_tracked(e.state)) e.state = FrameState::kAbandoned;
  }
}

void Tracker::forget_motion() {
  state_ = TrackingState::kNotInitialized;
  reset_wanted_ = false;
  lost_in_a_row_ = 0;
  last_ = Frame();
  has_velocity_ = false;
  reference_ = nullptr;
  local_keyframes_.clear();
  local_points_.clear();
}

void Tracker::discard_active_map() {
  const int discarded = map_.active_map();
  for (KeyFrame* kf : map_.discard_map(discarded))
    if (places_) places_->erase(kf);
  abandon_frames(discarded);
  const bool others_left = map_.n_keyframes() > 0;
  forget_motion();
  map_.begin_map();
  // With other maps left the next frame looks for itself in them first,
  // and starts a new map (the lost path) only where it cannot.
  if (others_left) state_ = TrackingState::kLost;
}

bool Tracker::can_initialize(const Frame& frame) const {
  // As ORB-SLAM2: enough keypoints overall, and points only where depth is known.
  int with_depth = 0;
  for (size_t i = 0; i < frame.size(); ++i) with_depth += frame.features.has_depth(i);
  return static_cast<int>(frame.size()) >= params_.min_init_points && with_depth >= 100;
}

bool Tracker::initialize(Frame& frame) {
  if (!can_initialize(frame)) return false;
  frame.T_cw = Pose::Identity();
  frame.has_pose = true;
  KeyFrame* kf = map_.create_keyframe(frame);
  const Pose T_wc = frame.T_cw.inverse();
  for (size_t i = 0; i < frame.size(); ++i) {
    if (!frame.features.has_depth(i)) continue;
    const cv::KeyPoint& kp = frame.features.keypoints[i];
    MapPoint* mp = map_.create_map_point(
        T_wc * frame.features.camera.unproject(kp.pt.x, kp.pt.y, frame.features.depth[i]), kf);
    mp->add_observation(kf, i);
    kf->add_map_point(mp, i);
    mp->update_descriptor();
    mp->update_normal_and_depth();
    frame.map_points[i] = mp;
  }
  mapper_.insert_keyframe(kf);
  reference_ = kf;
  frame.reference = kf;
  last_keyframe_frame_ = frame.id;
  local_keyframes_ = {kf};
  local_points_.clear();
  for (MapPoint* mp : kf->map_points)
    if (mp) local_points_.push_back(mp);
  state_ = TrackingState::kOk;
  last_ = frame;
  return true;
}

int Tracker::timed_optimize(Frame& frame) {
  ScopedTimer timer(current_stats_ ? &current_stats_->optimize_ms : nullptr);
  return optimize_pose(frame);
}

int Tracker::discard_outliers(Frame& frame) {
  int kept = 0;
  for (size_t i = 0; i < frame.size(); ++i) {
    MapPoint* mp = frame.map_points[i];
    if (!mp) continue;
    if (frame.outlier[i]) {
      frame.map_points[i] = nullptr;
      frame.outlier[i] = false;
      mp->last_seen_frame = frame.id;
    } else if (mp->n_observations() > 0) {
      ++kept;
    }
  }
  return kept;
}

bool Tracker::track_motion_model(Frame& frame, int& matches) {
  frame.T_cw = velocity_ * last_.T_cw;
  std::fill(frame.map_points.begin(), frame.map_points.end(), nullptr);
  {
    ScopedTimer timer(&current_stats_->match_ms);
    matches = match_by_projection(frame, last_, 15.0f);
    if (matches < 20) {
      std::fill(frame.map_points.begin(), frame.map_points.end(), nullptr);
      matches = match_by_projection(frame, last_, 30.0f);
    }
  }
  if (matches < 20) return false;
  timed_optimize(frame);
  frame.has_pose = true;
  return discard_outliers(frame) >= 10;
}

bool Tracker::track_reference_keyframe(Frame& frame, int& matches) {
  if (!reference_ || reference_->bad) return false;
  std::vector<MapPoint*> found;
  {
    ScopedTimer timer(&current_stats_->match_ms);
    matches = match_by_descriptor(*reference_, frame, found, 0.7f);
  }
  if (matches < 15) return false;
  frame.map_points = found;
  frame.T_cw = last_.T_cw;
  timed_optimize(frame);
  frame.has_pose = true;
  return discard_outliers(frame) >= 10;
}

bool Tracker::relocalize(Frame& frame, int& matches, int skip_map) {
  matches = 0;
  if (!places_) return false;
  // Any keyframe of the map that looks like the frame (place recognition),
  // best first; each is tried with BoW-guided matching, PnP RANSAC, pose
  // optimisation and a guided search in its neighbourhood.
  const std::vector<KeyFrame*> candidates = places_->relocalisation_candidates(frame, skip_map);
  int tried = 0;
  for (KeyFrame* kf : candidates) {
    if (kf->bad) continue;
    if (tried++ >= params_.relocalisation_candidates) break;
    std::vector<MapPoint*> found;
    int n;
    {
      ScopedTimer timer(&current_stats_->match_ms);
      n = match_by_bow(*kf, frame, found, 0.75f);
    }
    matches = std::max(matches, n);
    if (n < 15) continue;
    const PnpResult pnp = solve_pnp_ransac(found, frame.features);
    if (!pnp.ok) continue;
    std::fill(frame.map_points.begin(), frame.map_points.end(), nullptr);
    std::fill(frame.outlier.begin(), frame.outlier.end(), false);
    for (int i : pnp.inliers) frame.map_points[i] = found[i];
    frame.T_cw = pnp.T_cw;
    frame.has_pose = true;
    int good = timed_optimize(frame);
    if (good < 10) continue;
    discard_outliers(frame);
    if (good < params_.relocalisation_min_inliers) {
      // More matches from the candidate's neighbourhood by projection.
      std::vector<ProjectedPoint> projected;
      for (KeyFrame* n_kf : kf->covisibles(10))
        for (MapPoint* mp : n_kf->map_points) {
          ProjectedPoint p;
          if (mp && !mp->bad && project_into(*mp, frame.T_cw, frame.features, p))
            projected.push_back(p);
        }
      for (MapPoint* mp : kf->map_points) {
        ProjectedPoint p;
        if (mp && !mp->bad && project_into(*mp, frame.T_cw, frame.features, p))
          projected.push_back(p);
      }
      match_local_points(frame, projected, 5.0f);
      good = timed_optimize(frame);
      discard_outliers(frame);
    }
    if (good >= params_.relocalisation_min_inliers) {
      // Found in another map of the atlas: tracking goes on in that one.
      map_.activate(kf->map_id);
      must_relocalise_ = false;
      reference_ = kf;
      last_reloc_frame_ = frame.id;
      return true;
    }
  }
  std::fill(frame.map_points.begin(), frame.map_points.end(), nullptr);
  frame.has_pose = false;
  return false;
}

void Tracker::rejoin_older_map(Frame& frame) {
  const int young = map_.active_map();
  if (map_.n_keyframes_in(young) >= static_cast<size_t>(params_.young_map_keyframes) ||
      map_.map_ids().size() < 2)
    return;
  // The frame is tracked in the young map; if it also relocalises in an
  // older one, its two poses give the transform between the maps.
  Frame probe = frame;
  int matches = 0;
  if (!relocalize(probe, matches, young)) {
    reference_ = frame.reference;
    return;
  }
  const int older = map_.active_map();  // relocalize activated it
  const Pose T_older_young = probe.T_cw.inverse() * frame.T_cw;
  map_.merge_maps(young, older, T_older_young);
  ++rejoined_;
  // The last frame's pose follows its (moved) reference, so the motion
  // model stays right; tracking goes on with the older map's points.
  if (last_.has_pose && last_.reference) last_.T_cw = last_T_cr_ * last_.reference->T_cw;
  int inliers = 0, n_local = 0;
  probe.reference = reference_;
  if (track_local_map(probe, inliers, n_local)) {
    frame = std::move(probe);
  } else {
    frame.T_cw = frame.T_cw * T_older_young.inverse();
    reference_ = frame.reference;
  }
}

void Tracker::update_local_map(Frame& frame) {
  // Keyframes that see the frame's points, weighted by how many.
  std::map<KeyFrame*, int, ById> counter;
  for (size_t i = 0; i < frame.size(); ++i) {
    MapPoint* mp = frame.map_points[i];
    if (!mp) continue;
    if (mp->bad) {
      frame.map_points[i] = nullptr;
      continue;
    }
    for (auto& [kf, idx] : mp->observations) counter[kf]++;
  }
  local_keyframes_.clear();
  KeyFrame* best = nullptr;
  int best_count = 0;
  for (auto& [kf, n] : counter) {
    if (kf->bad) continue;
    if (n > best_count) best = kf, best_count = n;
    local_keyframes_.push_back(kf);
    kf->track_local_for = frame.id;
  }
  // Their best covisibles, children and parents, up to 80 keyframes.
  const size_t first_ring = local_keyframes_.size();
  for (size_t k = 0; k < first_ring && local_keyframes_.size() < 80; ++k) {
    KeyFrame* kf = local_keyframes_[k];
    auto add = [&](KeyFrame* n) {
      if (n && !n->bad && n->track_local_for != frame.id) {
        n->track_local_for = frame.id;
        local_keyframes_.push_back(n);
      }
    };
    for (KeyFrame* n : kf->covisibles(10)) add(n);
    for (KeyFrame* c : kf->children()) add(c);
    add(kf->parent());
  }
  if (best) {
    reference_ = best;
    frame.reference = best;
  }
  local_points_.clear();
  for (KeyFrame* kf : local_keyframes_)
    for (MapPoint* mp : kf->map_points)
      if (mp && !mp->bad && mp->local_map_for != frame.id) {
        mp->local_map_for = frame.id;
        local_points_.push_back(mp);
      }
}

bool Tracker::track_local_map(Frame& frame, int& inliers, int& n_local) {
  update_local_map(frame);
  // The visible/found counters steer the mapper's point culling; a
  // localisation-only run leaves the loaded map exactly as it was.
  const int counted = localisation_only_ ? 0 : 1;
  for (MapPoint* mp : frame.map_points)
    if (mp && !mp->bad) {
      mp->visible += counted;
      mp->last_seen_frame = frame.id;
    }
  std::vector<ProjectedPoint> projected;
  for (MapPoint* mp : local_points_) {
    if (mp->last_seen_frame == frame.id || mp->bad) continue;
    ProjectedPoint p;
    if (project_into(*mp, frame.T_cw, frame.features, p)) {
      mp->visible += counted;
      projected.push_back(p);
    }
  }
  n_local = static_cast<int>(local_points_.size());
  const bool recent_reloc = frame.id < last_reloc_frame_ + 2;
  if (!projected.empty()) {
    ScopedTimer timer(&current_stats_->match_ms);
    match_local_points(frame, projected, recent_reloc ? 5.0f : 3.0f);
  }
  timed_optimize(frame);
  inliers = 0;
  for (size_t i = 0; i < frame.size(); ++i) {
    MapPoint* mp = frame.map_points[i];
    if (!mp) continue;
    if (!frame.outlier[i]) {
      mp->found += counted;
      if (mp->n_observations() > 0) ++inliers;
    }
  }
  const int needed = frame.id < last_reloc_frame_ + params_.max_frames_between_kf
                         ? params_.relocalisation_min_inliers
                         : params_.local_map_min_inliers;
  return inliers >= needed;
}

bool Tracker::need_keyframe(const Frame& frame, int inliers) const {
  const int n_kfs = static_cast<int>(map_.n_keyframes_in(map_.active_map()));
  if (frame.id < last_reloc_frame_ + params_.max_frames_between_kf &&
      n_kfs > params_.max_frames_between_kf)
    return false;
  // ORB-SLAM2 counts the reference's points seen by 2 keyframes (3 once
  // the map has more than two); a map of one keyframe has only points of
  // one observation, which left it no reference count at all, so a second
  // keyframe came only from the close-point rule: with the few points
  // that have depth under rejection, never, and the map died young.
  const int min_obs = n_kfs <= 1 ? 1 : n_kfs <= 2 ? 2 : 3;
  const int ref_matches = reference_ ? reference_->tracked_map_points(min_obs) : 0;
  const bool idle = mapper_.idle();
  int tracked_close = 0, untracked_close = 0;
  const double close = frame.features.camera.close_depth;
  for (size_t i = 0; i < frame.size(); ++i) {
    const float z = frame.features.depth[i];
    if (z <= 0 || z >= close) continue;
    if (frame.map_points[i] && !frame.outlier[i])
      ++tracked_close;
    else
      ++untracked_close;
  }
  const bool need_close = tracked_close < 100 && untracked_close > 70;
  const double ref_ratio = n_kfs < 2 ? 0.4 : 0.75;
  const bool c1a = frame.id >= last_keyframe_frame_ + params_.max_frames_between_kf;
  const bool c1b = frame.id >= last_keyframe_frame_ + params_.min_frames_between_kf && idle;
  const bool weak = inliers < params_.weak_inliers;
  const bool c1c = inliers < ref_matches * 0.25 || need_close || weak;
  const bool c2 = (inliers < ref_matches * ref_ratio || need_close || weak) && inliers > 15;
  if (!((c1a || c1b || c1c) && c2)) return false;
  if (idle) return true;
  mapper_.interrupt_ba();
  return mapper_.queued() < 3;
}

void Tracker::create_keyframe(Frame& frame) {
  KeyFrame* kf = map_.create_keyframe(frame);
  reference_ = kf;
  frame.reference = kf;
  // New points from depth: all close keypoints without a point, and at least
  // the 100 nearest ones.
  std::vector<std::pair<float, size_t>> by_depth;
  for (size_t i = 0; i < frame.size(); ++i)
    if (frame.features.depth[i] > 0) by_depth.emplace_back(frame.features.depth[i], i);
  std::sort(by_depth.begin(), by_depth.end());
  const Pose T_wc = frame.T_cw.inverse();
  int created = 0;
  for (auto& [z, i] : by_depth) {
    MapPoint* existing = frame.map_points[i];
    const bool needs_point = !existing || existing->n_observations() < 1;
    if (needs_point) {
      const cv::KeyPoint& kp = frame.features.keypoints[i];
      MapPoint* mp =
          map_.create_map_point(T_wc * frame.features.camera.unproject(kp.pt.x, kp.pt.y, z), kf);
      mp->add_observation(kf, i);
      kf->add_map_point(mp, i);
      mp->update_descriptor();
      mp->update_normal_and_depth();
      frame.map_points[i] = mp;
    }
    ++created;
    if (z > frame.features.camera.close_depth && created > 100) break;
  }
  last_keyframe_frame_ = frame.id;
  mapper_.insert_keyframe(kf);
}

}  // namespace depot::slam
