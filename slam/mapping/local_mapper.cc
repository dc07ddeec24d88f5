#include "slam/mapping/local_mapper.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "common/error.h"
#include "slam/match/orb_matcher.h"
#include "slam/optimize/optimizer.h"
#include "slam/place/keyframe_database.h"

namespace depot::slam {

LocalMapper::LocalMapper(Map& map, bool threaded, KeyFrameDatabase* places)
    : map_(map), places_(places), worker_(threaded, [this](KeyFrame* kf) { process(kf); }) {}

LocalMapper::~LocalMapper() {
  stop();
}

void LocalMapper::insert_keyframe(KeyFrame* kf) {
  if (worker_.push(kf)) abort_ba_ = true;  // a new keyframe matters more than BA
}

bool LocalMapper::idle() const {
  return worker_.idle();
}

void LocalMapper::throw_if_failed() const {
  const std::exception_ptr failure = worker_.failure();
  if (!failure) return;
  try {
    std::rethrow_exception(failure);
  } catch (const std::exception& e) {
    fail("local mapping", e.what());
  } catch (...) {
    fail("local mapping", "stopped by an unknown exception");
  }
}

size_t LocalMapper::queued() const {
  return worker_.queued();
}

LocalMapperStats LocalMapper::stats() const {
  MutexLock lock(stats_mutex_);
  return stats_;
}

void LocalMapper::run_pending() {
  try {
    worker_.run_pending();
  } catch (...) {
    throw_if_failed();
    throw;
  }
}

void LocalMapper::reset() {
  worker_.clear();
  recent_points_.clear();
}

void LocalMapper::pause() {
  worker_.request_pause();
  abort_ba_ = true;  // after the request: process() reads both, in that order
  worker_.pause();
}

void LocalMapper::resume() {
  worker_.resume();
}

void LocalMapper::stop() {
  worker_.stop();
}

void LocalMapper::process(KeyFrame* kf) {
  // Bundle adjustment is skipped while keyframes wait; one that arrives
  // during it, or a pause, aborts it (insert_keyframe, pause).
  abort_ba_ = queued() > 0 || worker_.pause_requested();
  size_t n_keyframes = 0;
  // The bag of words reads only the keyframe's own descriptors: no lock.
  if (places_) places_->describe(*kf);
  // The map lock is taken step by step (and per neighbour while
  // triangulating), not for the whole keyframe: tracking waits for at most
  // one step, not for all of them.
  {
    MutexLock lock(map_.mutex());
    process_new_keyframe(kf);
    if (places_ && !kf->bad) places_->add(kf);
  }
  {
    MutexLock lock(map_.mutex());
    if (!kf->bad) cull_map_points(kf);
  }
  create_new_map_points(kf);
  {
    MutexLock lock(map_.mutex());
    if (queued() == 0 && !kf->bad) search_in_neighbors(kf);
    n_keyframes = map_.n_keyframes_in(kf->map_id);
  }
  if (queued() == 0 && n_keyframes > 2) {
    auto t0 = std::chrono::steady_clock::now();
    local_bundle_adjustment(kf, map_, &abort_ba_);
    MutexLock lock(stats_mutex_);
    stats_.ba_ms +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  }
  {
    MutexLock lock(map_.mutex());
    if (!kf->bad) cull_keyframes(kf);
  }
  if (next_ && !kf->bad) next_->insert_keyframe(kf);
  MutexLock lock(stats_mutex_);
  stats_.keyframes++;
}

void LocalMapper::process_new_keyframe(KeyFrame* kf) {
  // Every later step indexes keypoints through map_points.
  if (kf->map_points.size() != kf->features.size())
    fail("keyframe " + std::to_string(kf->id),
         "has " + std::to_string(kf->map_points.size()) + " map point slots for " +
             std::to_string(kf->features.size()) + " keypoints");
  for (size_t i = 0; i < kf->map_points.size(); ++i) {
    MapPoint* mp = kf->map_points[i];
    if (!mp) continue;
    if (mp->bad) {
      // Fused while the keyframe waited in the queue: it sees the survivor,
      // unless it holds that one already.
      MapPoint* survivor = follow_replacements(mp);
      const bool held = survivor && std::find(kf->map_points.begin(), kf->map_points.end(),
                                              survivor) != kf->map_points.end();
      if (!survivor || held || survivor->observations.count(kf)) {
        kf->erase_map_point(i);
        continue;
      }
      mp = survivor;
      kf->add_map_point(mp, i);
    }
    if (!mp->observations.count(kf)) {
      mp->add_observation(kf, i);
      mp->update_normal_and_depth();
      mp->update_descriptor();
    } else if (mp->first_keyframe_id == kf->id) {
      recent_points_.push_back(mp);  // created from this keyframe's depth
    }
  }
  kf->update_connections();
}

namespace {

// ORB-SLAM2's observation count for RGB-D: an observation with depth
// weighs 2 (it alone fixes the point), one without 1.
int weighted_observations(const MapPoint& mp) {
  int n = 0;
  for (const auto& [kf, index] : mp.observations) n += kf->features.has_depth(index) ? 2 : 1;
  return n;
}

}  // namespace

void LocalMapper::cull_map_points(KeyFrame* kf) {
  // New points must be found where predicted (a quarter of the times) and,
  // two keyframes later, be seen by more than a keyframe with depth and one
  // without (ORB-SLAM2: weighted observations > 3). Counting keyframes
  // instead culled points seen with depth from two keyframes: a turning
  // camera then lost its first map's points at the third keyframe.
  const long current = kf->id;
  for (auto it = recent_points_.begin(); it != recent_points_.end();) {
    MapPoint* mp = *it;
    bool erase = false;
    if (mp->bad) {
      it = recent_points_.erase(it);
      continue;
    }
    if (mp->found_ratio() < 0.25f) {
      erase = true;
    } else if (current - mp->first_keyframe_id >= 2 && weighted_observations(*mp) <= 3) {
      erase = true;
    } else if (current - mp->first_keyframe_id >= 3) {
      it = recent_points_.erase(it);  // survived: no longer recent
      continue;
    }
    if (erase) {
      mp->set_bad();
      map_.erase_map_point(mp);
      MutexLock lock(stats_mutex_);
      stats_.points_culled++;
      it = recent_points_.erase(it);
    } else {
      ++it;
    }
  }
}

void LocalMapper::create_new_map_points(KeyFrame* kf) {
  // Takes the map lock per neighbour (see process()).
  const Features& f1 = kf->features;
  const PinholeCamera& cam = f1.camera;
  const double baseline = cam.bf / cam.fx;
  std::vector<KeyFrame*> neighbours;
  {
    MutexLock lock(map_.mutex());
    neighbours = kf->covisibles(10);
  }
  for (KeyFrame* kf2 : neighbours) {
    if (queued() > 0) return;  // more keyframes waiting: keep up with tracking
    MutexLock lock(map_.mutex());
    if (kf->bad || kf2->bad) continue;
    const Eigen::Vector3d c1 = kf->camera_center();
    const Pose T1w = kf->T_cw;
    const Eigen::Vector3d c2 = kf2->camera_center();
    if ((c2 - c1).norm() < baseline) continue;
    std::vector<std::pair<size_t, size_t>> pairs;
    match_for_triangulation(*kf, *kf2, pairs);
    const Features& f2 = kf2->features;
    const Pose T2w = kf2->T_cw;
    for (auto [i1, i2] : pairs) {
      const cv::KeyPoint& k1 = f1.keypoints[i1];
      const cv::KeyPoint& k2 = f2.keypoints[i2];
      const Eigen::Vector3d r1 =
          T1w.linear().transpose() * cam.unproject(k1.pt.x, k1.pt.y, 1.0).normalized();
      const Eigen::Vector3d r2 =
          T2w.linear().transpose() * cam.unproject(k2.pt.x, k2.pt.y, 1.0).normalized();
      const double parallax_cos = r1.dot(r2);
      // With depth, a stereo-like parallax bound tells which is more precise.
      double depth_cos1 = 2.0, depth_cos2 = 2.0;
      if (f1.depth[i1] > 0) depth_cos1 = std::cos(2 * std::atan2(baseline / 2, f1.depth[i1]));
      if (f2.depth[i2] > 0) depth_cos2 = std::cos(2 * std::atan2(baseline / 2, f2.depth[i2]));
      const double depth_cos = std::min(depth_cos1, depth_cos2);
      Eigen::Vector3d x;
      if (parallax_cos < depth_cos && parallax_cos > 0 && parallax_cos < 0.9998) {
        // Linear triangulation (DLT) from the two views.
        Eigen::Matrix<double, 4, 4> A;
        Eigen::Matrix<double, 3, 4> P1, P2;
        P1 << T1w.linear(), T1w.translation();
        P2 << T2w.linear(), T2w.translation();
        const Eigen::Vector3d n1 = cam.unproject(k1.pt.x, k1.pt.y, 1.0),
                              n2 = cam.unproject(k2.pt.x, k2.pt.y, 1.0);
        A.row(0) = n1.x() * P1.row(2) - P1.row(0);
        A.row(1) = n1.y() * P1.row(2) - P1.row(1);
        A.row(2) = n2.x() * P2.row(2) - P2.row(0);
        A.row(3) = n2.y() * P2.row(2) - P2.row(1);
        Eigen::JacobiSVD<Eigen::Matrix4d> svd(A, Eigen::ComputeFullV);
        Eigen::Vector4d h = svd.matrixV().col(3);
        if (std::abs(h(3)) < 1e-12) continue;
        x = h.head<3>() / h(3);
      } else if (depth_cos1 < depth_cos2) {
        x = T1w.inverse() * cam.unproject(k1.pt.x, k1.pt.y, f1.depth[i1]);
      } else if (depth_cos2 < depth_cos1) {
        x = T2w.inverse() * cam.unproject(k2.pt.x, k2.pt.y, f2.depth[i2]);
      } else {
        continue;  // low parallax and no depth
      }
      // In front of both cameras, small reprojection error, consistent scale.
      const Eigen::Vector3d p1 = T1w * x, p2 = T2w * x;
      if (p1.z() <= 0 || p2.z() <= 0) continue;
      auto reproj_ok = [&](const Features& f, size_t i, const Eigen::Vector3d& pc) {
        const cv::KeyPoint& kp = f.keypoints[i];
        const Eigen::Vector2d uv = cam.project(pc);
        const double ex = uv.x() - kp.pt.x, ey = uv.y() - kp.pt.y;
        const double s2 = f.levels->sigma2[kp.octave];
        if (f.u_right[i] >= 0) {
          const double er = (uv.x() - cam.bf / pc.z()) - f.u_right[i];
          return ex * ex + ey * ey + er * er <= 7.8 * s2;
        }
        return ex * ex + ey * ey <= 5.991 * s2;
      };
      if (!reproj_ok(f1, i1, p1) || !reproj_ok(f2, i2, p2)) continue;
      const double d1 = (x - c1).norm(), d2 = (x - c2).norm();
      if (d1 <= 0 || d2 <= 0) continue;
      const double ratio_dist = d2 / d1;
      const double ratio_octave = f1.levels->scale[k1.octave] / f1.levels->scale[k2.octave];
      const double factor = 1.5 * f1.levels->scale_factor;
      if (ratio_dist * factor < ratio_octave || ratio_dist > ratio_octave * factor) continue;
      if (kf->map_points[i1] || kf2->map_points[i2]) continue;
      MapPoint* mp = map_.create_map_point(x, kf);
      mp->add_observation(kf, i1);
      mp->add_observation(kf2, i2);
      kf->add_map_point(mp, i1);
      kf2->add_map_point(mp, i2);
      mp->update_descriptor();
      mp->update_normal_and_depth();
      recent_points_.push_back(mp);
      MutexLock lock(stats_mutex_);
      stats_.points_created++;
    }
  }
}

void LocalMapper::search_in_neighbors(KeyFrame* kf) {
  // Neighbours and their neighbours.
  std::vector<KeyFrame*> targets;
  for (KeyFrame* n : kf->covisibles(10)) {
    if (n->bad || n->fuse_target_for == kf->id) continue;
    n->fuse_target_for = kf->id;
    targets.push_back(n);
    for (KeyFrame* n2 : n->covisibles(5))
      if (!n2->bad && n2 != kf && n2->fuse_target_for != kf->id) {
        n2->fuse_target_for = kf->id;
        targets.push_back(n2);
      }
  }
  std::vector<MapPoint*> own;
  for (MapPoint* mp : kf->map_points)
    if (mp && !mp->bad) own.push_back(mp);
  for (KeyFrame* t : targets) fuse(t, own, 3.0f);
  std::vector<MapPoint*> theirs;
  for (KeyFrame* t : targets)
    for (MapPoint* mp : t->map_points)
      if (mp && !mp->bad && mp->fuse_candidate_for != kf->id) {
        mp->fuse_candidate_for = kf->id;
        theirs.push_back(mp);
      }
  fuse(kf, theirs, 3.0f);
  for (MapPoint* mp : kf->map_points)
    if (mp && !mp->bad) {
      mp->update_descriptor();
      mp->update_normal_and_depth();
    }
  kf->update_connections();
}

void LocalMapper::cull_keyframes(KeyFrame* kf) {
  // A keyframe is redundant when 90 % of its close points are seen by at
  // least three other keyframes at the same or a finer scale.
  const double close = kf->features.camera.close_depth;
  for (KeyFrame* n : kf->covisibles()) {
    if (n->map_origin || n->bad) continue;
    int redundant = 0, total = 0;
    for (size_t i = 0; i < n->map_points.size(); ++i) {
      MapPoint* mp = n->map_points[i];
      if (!mp || mp->bad) continue;
      const float z = n->features.depth[i];
      if (z > close || z < 0) continue;
      ++total;
      if (mp->n_observations() <= 3) continue;
      const int level = n->features.keypoints[i].octave;
      int seen = 0;
      for (auto& [other, idx] : mp->observations) {
        if (other == n) continue;
        if (other->features.keypoints[idx].octave <= level + 1) ++seen;
        if (seen >= 3) break;
      }
      if (seen >= 3) ++redundant;
    }
    if (total > 0 && redundant > 0.9 * total) {
      n->set_bad();
      if (!n->bad) continue;  // kept: it holds a loop edge
      map_.erase_keyframe(n);
      if (places_) places_->erase(n);
      MutexLock lock(stats_mutex_);
      stats_.keyframes_culled++;
    }
  }
}

}  // namespace depot::slam
