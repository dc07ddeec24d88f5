#include "slam/loop/loop_closer.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "slam/data/map_point.h"
#include "slam/mapping/local_mapper.h"
#include "slam/match/orb_matcher.h"
#include "slam/optimize/optimizer.h"
#include "slam/optimize/pose_graph.h"
#include "slam/place/keyframe_database.h"
#include "slam/solve/pnp_ransac.h"
#include "slam/solve/rigid_ransac.h"

namespace depot::slam {

struct LoopCloser::Loop {
  KeyFrame* matched = nullptr;
  Pose T_cw = Pose::Identity();        // the closing keyframe's corrected pose
  std::vector<MapPoint*> matches;      // per keypoint of the closing keyframe
  std::vector<MapPoint*> loop_points;  // the matched keyframe's neighbourhood
  int n_matches = 0;
};

namespace {

// A keyframe seen as a frame to match into (no map points yet).
Frame frame_view(const KeyFrame& kf) {
  Frame f(kf.frame_id, kf.timestamp, kf.features);
  f.bow = kf.bow;
  f.bow_features = kf.bow_features;
  f.T_cw = kf.T_cw;
  f.has_pose = true;
  return f;
}

}  // namespace

LoopCloser::LoopCloser(Map& map, KeyFrameDatabase& places, LocalMapper& mapper, bool threaded,
                       const LoopCloserParams& params)
    : map_(map),
      places_(places),
      mapper_(mapper),
      params_(params),
      global_(map, mapper, threaded, params.global_ba_iterations),
      worker_(threaded, [this](KeyFrame* kf) { process(kf); }) {}

LoopCloser::~LoopCloser() {
  stop();
}

void LoopCloser::insert_keyframe(KeyFrame* kf) {
  worker_.push(kf);
}

bool LoopCloser::idle() const {
  return worker_.idle() && !global_.running();
}

size_t LoopCloser::queued() const {
  return worker_.queued();
}

std::exception_ptr LoopCloser::failure() const {
  if (std::exception_ptr e = worker_.failure()) return e;
  return global_.failure();
}

int LoopCloser::refused() const {
  MutexLock lock(stats_mutex_);
  return implausible_;
}

int LoopCloser::unconfirmed_merges() const {
  MutexLock lock(stats_mutex_);
  return unconfirmed_merges_;
}

std::vector<LoopClosure> LoopCloser::closures() const {
  MutexLock lock(stats_mutex_);
  return closures_;
}

void LoopCloser::run_pending() {
  worker_.run_pending();
}

void LoopCloser::reset() {
  worker_.clear();
  global_.abort();
  MutexLock map_lock(map_.mutex());
  consistent_groups_.clear();
  last_loop_keyframe_ = -1;
}

void LoopCloser::stop() {
  worker_.stop();
  global_.wait();
}

void LoopCloser::process(KeyFrame* kf) {
  std::vector<KeyFrame*> candidates;
  Loop loop;
  {
    MutexLock lock(map_.mutex());
    if (kf->bad || !detect(kf, candidates)) return;
    if (!compute_transform(kf, candidates, loop)) return;
  }
  // A running global adjustment solves a map this correction changes.
  global_.abort();
  const bool is_merge = loop.matched->map_id != kf->map_id;
  if (is_merge) {
    bool confirmed;
    {
      MutexLock lock(map_.mutex());
      confirmed = !kf->bad && !loop.matched->bad && confirmed_by_neighbours(kf, loop);
    }
    if (!confirmed) {
      MutexLock qlock(stats_mutex_);
      ++unconfirmed_merges_;
      return;
    }
  }
  const bool changed = is_merge ? merge(kf, loop) : correct(kf, loop);
  if (changed && params_.global_ba_iterations > 0) global_.start();
}

bool LoopCloser::detect(KeyFrame* kf, std::vector<KeyFrame*>& out) {
  out.clear();
  // Loops within kf's map wait until it is grown and the last loop is a few
  // keyframes behind; merges with another map never wait.
  const bool loops_allowed =
      static_cast<long>(map_.n_keyframes_in(kf->map_id)) > params_.keyframes_between_loops &&
      !(last_loop_keyframe_ >= 0 && kf->id < last_loop_keyframe_ + params_.keyframes_between_loops);
  // A loop candidate must look at least as much like kf as its least
  // similar covisible keyframe does.
  double min_score = 1;
  for (KeyFrame* c : kf->covisibles())
    min_score = std::min(min_score, bow_similarity(kf->bow, c->bow));
  std::vector<KeyFrame*> candidates = places_.loop_candidates(*kf, min_score);
  candidates.erase(
      std::remove_if(candidates.begin(), candidates.end(),
                     [&](const KeyFrame* c) { return c->map_id == kf->map_id && !loops_allowed; }),
      candidates.end());
  if (candidates.empty()) {
    consistent_groups_.clear();
    return false;
  }
  // Consistency: a candidate's group (it and its covisibles) must share a
  // keyframe with a group seen for the previous keyframes.
  decltype(consistent_groups_) current;
  std::vector<bool> previous_extended(consistent_groups_.size(), false);
  for (KeyFrame* candidate : candidates) {
    std::set<KeyFrame*, ById> group;
    group.insert(candidate);
    for (KeyFrame* c : candidate->covisibles()) group.insert(c);
    bool consistent_with_any = false;
    bool accepted = false;
    for (size_t g = 0; g < consistent_groups_.size(); ++g) {
      // Not a structured binding: C++17 lambdas may not capture one (clang refuses).
      const std::set<KeyFrame*, ById>& previous = consistent_groups_[g].first;
      const int count = consistent_groups_[g].second;
      const bool shares = std::any_of(group.begin(), group.end(),
                                      [&](KeyFrame* k) { return previous.count(k) > 0; });
      if (!shares) continue;
      consistent_with_any = true;
      if (!previous_extended[g]) {
        current.push_back({group, count + 1});
        previous_extended[g] = true;
      }
      if (count + 1 >= params_.consistency && !accepted) {
        out.push_back(candidate);
        accepted = true;
      }
    }
    if (!consistent_with_any) current.push_back({group, 0});
  }
  consistent_groups_ = std::move(current);
  return !out.empty();
}

bool LoopCloser::compute_transform(KeyFrame* kf, const std::vector<KeyFrame*>& candidates,
                                   Loop& loop) {
  const Features& f = kf->features;
  for (KeyFrame* candidate : candidates) {
    if (candidate->bad) continue;
    Frame view = frame_view(*kf);
    std::vector<MapPoint*> found;
    if (match_by_bow(*candidate, view, found, 0.75f) < params_.min_bow_matches) continue;
    std::vector<RigidCorrespondence> pairs;
    std::vector<size_t> keypoint_of;
    for (size_t i = 0; i < found.size(); ++i) {
      MapPoint* mp = found[i];
      if (!mp) continue;
      // kf's own 3-D point for the keypoint: its map point (also those
      // triangulated beyond the depth range), else its depth.
      Eigen::Vector3d in_a;
      const MapPoint* own = kf->map_points[i];
      if (own && !own->bad)
        in_a = kf->T_cw * own->position;
      else if (f.has_depth(i))
        in_a = f.camera.unproject(f.keypoints[i].pt.x, f.keypoints[i].pt.y, f.depth[i]);
      else
        continue;
      auto obs = mp->observations.find(candidate);
      if (obs == mp->observations.end()) continue;
      const cv::KeyPoint& kp = f.keypoints[i];
      const cv::KeyPoint& kp_b = candidate->features.keypoints[obs->second];
      RigidCorrespondence c;
      c.in_a = in_a;
      c.in_b = mp->position;
      c.pixel_a = {kp.pt.x, kp.pt.y};
      c.pixel_b = {kp_b.pt.x, kp_b.pt.y};
      c.T_b_camera = candidate->T_cw;
      c.max_error_px = std::sqrt(9.21 * f.levels->sigma2[std::max(kp.octave, kp_b.octave)]);
      pairs.push_back(c);
      keypoint_of.push_back(i);
    }
    // The corrected pose of kf: rigid from 3-D/3-D pairs where kf knows its
    // points; when too few do (the loop seen from beyond the depth range),
    // from 3-D/2-D pairs with PnP, as relocalisation does: scale is known
    // either way.
    std::vector<size_t> inliers;
    Pose T_cw;
    const RigidResult rigid = solve_rigid_ransac(pairs, f.camera, 300, params_.min_rigid_inliers,
                                                 static_cast<uint64_t>(kf->id) + 1);
    if (rigid.ok) {
      T_cw = rigid.T_ab;
      for (int k : rigid.inliers) inliers.push_back(keypoint_of[k]);
    } else {
      const PnpResult pnp = solve_pnp_ransac(found, f, 300, 4.0, params_.min_rigid_inliers);
      if (!pnp.ok) continue;
      T_cw = pnp.T_cw;
      for (int i : pnp.inliers) inliers.push_back(static_cast<size_t>(i));
    }
    // Refine the pose against the inlier points (held fixed), as tracking does.
    std::fill(view.map_points.begin(), view.map_points.end(), nullptr);
    for (size_t i : inliers) view.map_points[i] = found[i];
    view.T_cw = T_cw;
    if (optimize_pose(view) < params_.min_rigid_inliers) continue;
    for (size_t i = 0; i < view.size(); ++i)
      if (view.outlier[i]) view.map_points[i] = nullptr, view.outlier[i] = false;
    // The loop's map points: the candidate's and its covisibles'.
    std::vector<MapPoint*> loop_points;
    std::vector<KeyFrame*> around = candidate->covisibles();
    around.push_back(candidate);
    std::set<MapPoint*, ById> seen;
    for (KeyFrame* k : around)
      for (MapPoint* mp : k->map_points)
        if (mp && !mp->bad && seen.insert(mp).second) loop_points.push_back(mp);
    std::vector<ProjectedPoint> projected;
    for (MapPoint* mp : loop_points) {
      ProjectedPoint p;
      if (project_into(*mp, view.T_cw, f, p)) projected.push_back(p);
    }
    match_local_points(view, projected, 3.0f);
    int n = 0;
    for (MapPoint* mp : view.map_points) n += mp != nullptr;
    if (n < params_.min_loop_matches) continue;
    if (candidate->map_id == kf->map_id && !plausible_correction(*kf, *candidate, view.T_cw)) {
      MutexLock qlock(stats_mutex_);
      ++implausible_;
      continue;
    }
    loop.matched = candidate;
    loop.T_cw = view.T_cw;
    loop.matches = view.map_points;
    loop.loop_points = std::move(loop_points);
    loop.n_matches = n;
    return true;
  }
  return false;
}

namespace {

// Path length through the keyframes of one map with ids in [from_id, to_id].
double path_between(const Map& map, int map_id, long from_id, long to_id)
    DEPOT_REQUIRES(map.mutex()) {
  double path = 0;
  const KeyFrame* previous = nullptr;
  for (const KeyFrame* k : map.keyframes()) {
    if (k->id < from_id || k->id > to_id || k->map_id != map_id) continue;
    if (previous) path += (k->camera_center() - previous->camera_center()).norm();
    previous = k;
  }
  return path;
}

}  // namespace

bool LoopCloser::plausible_correction(const KeyFrame& kf, const KeyFrame& matched,
                                      const Pose& T_cw) const {
  const double path =
      path_between(map_, kf.map_id, std::min(kf.id, matched.id), std::max(kf.id, matched.id));
  const Pose change = T_cw * kf.T_cw.inverse();
  const double moved = (kf.camera_center() - T_cw.inverse().translation()).norm();
  const double turned = Eigen::AngleAxisd(change.linear()).angle();
  return moved <= params_.max_correction_m + params_.drift_per_m * path &&
         turned <= params_.max_rotation_rad + params_.rotation_per_m * path;
}

bool LoopCloser::correct(KeyFrame* kf, Loop& loop) {
  const MappingPause paused(mapper_);  // resumed after the map lock is released
  {
    MutexLock lock(map_.mutex());
    if (kf->bad || loop.matched->bad) return false;
    kf->update_connections();
    std::vector<KeyFrame*> connected = kf->covisibles();
    connected.push_back(kf);
    // Poses of kf's neighbourhood moved rigidly with kf's correction.
    std::map<KeyFrame*, Pose, ById> original, corrected;
    const Pose T_wc = kf->T_cw.inverse();
    for (KeyFrame* c : connected) {
      original[c] = c->T_cw;
      corrected[c] = c == kf ? loop.T_cw : c->T_cw * T_wc * loop.T_cw;
    }
    const double moved_m = (kf->camera_center() - loop.T_cw.inverse().translation()).norm();
    for (KeyFrame* c : connected) {
      const Pose move = corrected[c].inverse() * original[c];
      for (MapPoint* mp : c->map_points) {
        if (!mp || mp->bad || mp->loop_corrected_for == kf->id) continue;
        mp->position = move * mp->position;
        mp->loop_corrected_for = kf->id;
        mp->loop_reference = c;
      }
      c->T_cw = corrected[c];
    }
    for (KeyFrame* c : connected)
      for (MapPoint* mp : c->map_points)
        if (mp && !mp->bad) mp->update_normal_and_depth();
    const auto links = fuse_across(kf, loop, connected);
    optimize_essential_graph(kf, loop.matched, original, links);
    kf->loop_edges.insert(loop.matched);
    loop.matched->loop_edges.insert(kf);
    last_loop_keyframe_ = kf->id;
    MutexLock qlock(stats_mutex_);
    closures_.push_back({kf->id, loop.matched->id, kf->timestamp, loop.n_matches, moved_m,
                         path_between(map_, kf->map_id, loop.matched->id, kf->id)});
  }
  return true;
}

std::map<KeyFrame*, std::set<KeyFrame*, ById>, ById> LoopCloser::fuse_across(
    KeyFrame* kf, const Loop& loop, const std::vector<KeyFrame*>& connected) {
  // The loop's points take the place of kf's duplicates.
  for (size_t i = 0; i < loop.matches.size(); ++i) {
    MapPoint* loop_mp = loop.matches[i];
    if (!loop_mp || loop_mp->bad) continue;
    MapPoint* mine = kf->map_points[i];
    if (mine == loop_mp) continue;
    if (mine && !mine->bad) {
      mine->replace(loop_mp);
    } else {
      kf->add_map_point(loop_mp, i);
      loop_mp->add_observation(kf, i);
      loop_mp->update_descriptor();
    }
  }
  for (KeyFrame* c : connected) fuse(c, loop.loop_points, 4.0f);
  // Links the fusion made across the loop.
  std::set<KeyFrame*, ById> connected_set(connected.begin(), connected.end());
  std::map<KeyFrame*, std::set<KeyFrame*, ById>, ById> links;
  for (KeyFrame* c : connected) {
    if (c->bad) continue;
    const std::vector<KeyFrame*> before = c->covisibles();
    c->update_connections();
    for (KeyFrame* n : c->covisibles())
      if (!connected_set.count(n) && std::find(before.begin(), before.end(), n) == before.end())
        links[c].insert(n);
  }
  links[kf].insert(loop.matched);
  return links;
}

bool LoopCloser::confirmed_by_neighbours(KeyFrame* kf, const Loop& loop) const {
  // Where kf's pose goes, its neighbours go with it (one rigid move of kf's
  // map): each must see the other map's points where that move puts them.
  const Pose T_kf_old_to_new = kf->T_cw.inverse() * loop.T_cw;
  int confirmed = 0;
  for (KeyFrame* c : kf->covisibles(static_cast<size_t>(params_.merge_neighbours))) {
    if (c->bad) continue;
    Frame view = frame_view(*c);
    view.T_cw = c->T_cw * T_kf_old_to_new;
    std::vector<ProjectedPoint> projected;
    for (MapPoint* mp : loop.loop_points) {
      ProjectedPoint p;
      if (!mp->bad && project_into(*mp, view.T_cw, c->features, p)) projected.push_back(p);
    }
    match_local_points(view, projected, 3.0f);
    int n = 0;
    for (MapPoint* mp : view.map_points) n += mp != nullptr;
    if (n >= params_.merge_neighbour_matches && ++confirmed >= params_.merge_confirmations)
      return true;
  }
  return false;
}

bool LoopCloser::merge(KeyFrame* kf, Loop& loop) {
  const MappingPause paused(mapper_);  // resumed after the map lock is released
  {
    MutexLock lock(map_.mutex());
    if (kf->bad || loop.matched->bad || kf->map_id == loop.matched->map_id) return false;
    const int kf_map = kf->map_id, matched_map = loop.matched->map_id;
    // kf's map frame into the matched map's: kf is at loop.T_cw there.
    const Pose T_matched_kf = loop.T_cw.inverse() * kf->T_cw;
    // The smaller map moves; the larger keeps its frame.
    const size_t n_kf_map = map_.n_keyframes_in(kf_map);
    const size_t n_matched_map = map_.n_keyframes_in(matched_map);
    const bool kf_map_moves = n_kf_map <= n_matched_map;
    if (kf_map_moves)
      map_.merge_maps(kf_map, matched_map, T_matched_kf);
    else
      map_.merge_maps(matched_map, kf_map, T_matched_kf.inverse());
    std::vector<KeyFrame*> connected = kf->covisibles();
    connected.push_back(kf);
    const auto links = fuse_across(kf, loop, connected);
    (void)links;  // the global bundle adjustment welds the seam
    kf->loop_edges.insert(loop.matched);
    loop.matched->loop_edges.insert(kf);
    last_loop_keyframe_ = kf->id;
    MutexLock qlock(stats_mutex_);
    LoopClosure record;
    record.keyframe = kf->id;
    record.matched = loop.matched->id;
    record.timestamp = kf->timestamp;
    record.matches = loop.n_matches;
    record.merge = true;
    record.moved_map = kf_map_moves ? kf_map : matched_map;
    record.into_map = kf_map_moves ? matched_map : kf_map;
    record.moved_keyframes = static_cast<int>(kf_map_moves ? n_kf_map : n_matched_map);
    closures_.push_back(record);
  }
  return true;
}

void LoopCloser::optimize_essential_graph(
    KeyFrame* kf, KeyFrame* matched, const std::map<KeyFrame*, Pose, ById>& original,
    const std::map<KeyFrame*, std::set<KeyFrame*, ById>, ById>& links) {
  // kf's map only: the atlas's other maps share nothing with it.
  const std::vector<KeyFrame*> nodes = map_.keyframes_in(kf->map_id);
  std::map<const KeyFrame*, size_t> index;
  std::vector<Pose> poses;
  std::vector<bool> fixed;
  for (KeyFrame* k : nodes) {
    index[k] = poses.size();
    poses.push_back(k->T_cw);
    fixed.push_back(k->map_origin);
  }
  // Measurements from the poses before this correction: the graph keeps the
  // map's shape and spreads the loop's error along it.
  auto before = [&](KeyFrame* k) {
    auto it = original.find(k);
    return it == original.end() ? k->T_cw : it->second;
  };
  std::vector<PoseGraphEdge> edges;
  std::set<std::pair<size_t, size_t>> added;
  auto add = [&](KeyFrame* a, KeyFrame* b, const Pose& T_ab) {
    auto ia = index.find(a), ib = index.find(b);
    if (ia == index.end() || ib == index.end() || a == b) return;
    const auto key = std::minmax(ia->second, ib->second);
    if (!added.insert(key).second) return;
    edges.push_back({ia->second, ib->second, T_ab});
  };
  // The new loop links, measured with the corrected poses: they carry the loop.
  for (const auto& [a, others] : links)
    for (KeyFrame* b : others)
      if ((a == kf && b == matched) || a->weight(b) >= params_.essential_min_weight)
        add(a, b, a->T_cw * b->T_cw.inverse());
  for (KeyFrame* k : nodes) {
    if (KeyFrame* p = k->parent(); p && !p->bad) add(k, p, before(k) * before(p).inverse());
    for (KeyFrame* l : k->loop_edges) add(k, l, before(k) * before(l).inverse());
    for (KeyFrame* c : k->covisibles_with_weight(params_.essential_min_weight))
      add(k, c, before(k) * before(c).inverse());
  }
  std::vector<Pose> optimized = poses;
  optimize_pose_graph(optimized, fixed, edges);
  // Points move with their keyframe: the one a correction moved them with,
  // else their reference (or any observer when that one is gone).
  std::map<const KeyFrame*, std::pair<Pose, Pose>> change;  // before, after
  for (size_t i = 0; i < nodes.size(); ++i) {
    change[nodes[i]] = {nodes[i]->T_cw, optimized[i]};
    nodes[i]->T_cw = optimized[i];
  }
  for (MapPoint* mp : map_.map_points()) {
    if (mp->bad) continue;
    KeyFrame* ref = mp->loop_corrected_for == kf->id ? mp->loop_reference : mp->reference;
    if (!ref || ref->bad || !change.count(ref)) {
      ref = nullptr;
      for (auto& [k, idx] : mp->observations)
        if (!k->bad && change.count(k)) {
          ref = k;
          break;
        }
    }
    if (!ref) continue;
    const auto& [T_before, T_after] = change[ref];
    mp->position = T_after.inverse() * (T_before * mp->position);
    mp->update_normal_and_depth();
  }
}

}  // namespace depot::slam
