#pragma once
// Non-linear least squares on the map, in the manner of ORB-SLAM2's Optimizer
// but solved with Ceres: pose-only optimisation of a tracked frame, local
// bundle adjustment around a new keyframe and global bundle adjustment.
//
// Residuals are reprojection errors in pixels weighted by sqrt(1 / sigma^2) of
// the keypoint's pyramid level. A keypoint with depth gives a 3-D "stereo"
// residual (u, v, u_r) with u_r = u - bf / z, one without depth a 2-D (u, v)
// residual. chi2 = squared weighted error; the outlier thresholds are the 95 %
// chi-square quantiles (7.815 for 3 dof, 5.991 for 2 dof), and the Huber loss
// uses their square roots as its width.
#include <atomic>
#include <cstddef>
#include <utility>
#include <vector>

#include "slam/data/frame.h"
#include "slam/data/keyframe.h"
#include "slam/data/map.h"

namespace depot::slam {

inline constexpr double kChi2Mono = 5.991;    // 2 dof, 95 %
inline constexpr double kChi2Stereo = 7.815;  // 3 dof, 95 %

// Optimises frame.T_cw from the frame's matched map points (non-null, not bad;
// their positions are held fixed). Four rounds of 10 Levenberg-Marquardt
// iterations; after each round every correspondence is classified by its chi2
// and frame.outlier[i] set; outliers sit out the next round but are re-tested
// (and re-admitted) after it. The last round has no robust loss. Returns the
// number of inliers; with fewer than 3 correspondences returns 0 and leaves the
// pose alone. Reads map points without locking: the caller holds whatever lock
// protects them (tracking holds map.mutex()).
int optimize_pose(Frame& frame);

struct LocalBaOptions {
  int iterations_first = 5;    // with Huber loss, all observations
  int iterations_second = 10;  // with Huber loss, outliers of the first pass dropped
  // The most covisible neighbours optimised with kf. ORB-SLAM2 takes all of
  // them; in dynamic scenes RGB-D tracking spawns many mutually covisible
  // keyframes and the full window makes BA slower than the frame rate.
  size_t max_local_keyframes = 20;
};

// Local bundle adjustment around `kf`: optimises the poses of kf and its
// non-bad covisible keyframes and all non-bad map points they see; keyframes
// that observe those points but are not local are held fixed, as is the map's
// first keyframe (id 0). Observations that end with chi2 above threshold or
// behind the camera are unlinked from keyframe and point.
//
// Locking: the caller must NOT hold map.mutex(). It is taken to collect the
// problem, released while Ceres solves, and taken again to write poses,
// positions and erasures back (keyframes / points that turned bad in between
// are skipped). `abort` (may be null) is polled between iterations; set before
// the call, or during the first pass, nothing changes; set during the second
// pass, the first pass's result is applied.
void local_bundle_adjustment(KeyFrame* kf, Map& map, const std::atomic<bool>* abort,
                             const LocalBaOptions& options = {}) DEPOT_EXCLUDES(map.mutex());

// Bundle adjustment of the whole map (after a loop closure): every non-bad
// keyframe's pose (the map's first keyframe fixed) and every non-bad point,
// `iterations` Levenberg-Marquardt iterations with the Huber loss, all
// observations kept (ORB-SLAM2's global BA). The result is returned, not
// written: keyframes and points made while it ran must be moved with it,
// which is the caller's job (loop/global_adjuster).
//
// Locking: the caller must NOT hold map.mutex(); it is taken only to collect
// the problem. `abort` (may be null) is polled between iterations; an
// aborted or failed run returns completed = false.
struct GlobalBaResult {
  bool completed = false;
  std::vector<std::pair<KeyFrame*, Pose>> keyframes;
  std::vector<std::pair<MapPoint*, Eigen::Vector3d>> points;
};
GlobalBaResult global_bundle_adjustment(Map& map, const std::atomic<bool>* abort,
                                        int iterations = 10) DEPOT_EXCLUDES(map.mutex());

// RMS pixel distance between the (u, v) keypoints of `kf` and the projections
// of their non-bad map points (points behind the camera count too, with their
// projected error). `n_used` receives the number of terms. Returns 0 when there
// are none. No locking.
double reprojection_rmse(const KeyFrame* kf, size_t* n_used = nullptr);

// Pooled RMS over all keyframes of the map. No locking.
double reprojection_rmse(const Map& map) DEPOT_REQUIRES(map.mutex());

}  // namespace depot::slam
