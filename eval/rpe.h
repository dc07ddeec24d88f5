#pragma once
// Relative pose error (evo_rpe, TUM evaluate_rpe.py): for each selected pair
// (i, j) of matched poses, with Q the ground truth and P the estimate,
//   E_ij = (Q_i^-1 Q_j)^-1 (P_i^-1 P_j),
// translational error = |translation(E_ij)| in m, rotational error = rotation
// angle of E_ij in degrees. No alignment is needed: E is unchanged when
// either whole trajectory is moved rigidly.
#include <vector>

#include "common/pose.h"
#include "eval/matched_trajectories.h"
#include "eval/rpe_pairs.h"
#include "eval/statistics.h"

namespace depot::eval {

struct RpeResult {
  PairSelection selection;
  std::vector<PosePair> pairs;      // indices into the matched poses
  std::vector<double> stamps;       // ground-truth stamp of pose i of each pair
  std::vector<double> translation;  // m, one per pair
  std::vector<double> rotation;     // deg, one per pair
  ErrorStatistics translation_statistics;
  ErrorStatistics rotation_statistics;
};

Pose relative_pose_error(const Pose& reference_i, const Pose& reference_j, const Pose& estimate_i,
                         const Pose& estimate_j);

// Rotation angle of a pose in degrees, in [0, 180].
double rotation_angle_deg(const Pose& pose);

// Pairs are chosen on the ground-truth stamps of the matched poses. Throws
// depot::Error naming the estimate when no pair fits the delta.
RpeResult compute_rpe(const MatchedTrajectories& matched, const PairSelection& selection = {});

}  // namespace depot::eval
