#pragma once
// Absolute trajectory error (TUM evaluate_ate.py, evo `evo_ape tum gt est -a`):
// the estimate's positions are aligned to the ground truth's, then each
// matched pose contributes |p_gt - (s R p_est + t)|, in metres.
#include <vector>

#include <Eigen/Core>

#include "eval/alignment.h"
#include "eval/matched_trajectories.h"
#include "eval/statistics.h"

namespace depot::eval {

struct AteOptions {
  AlignmentKind alignment = AlignmentKind::kRigid;
};

struct AteResult {
  AlignmentKind alignment_kind = AlignmentKind::kRigid;
  SimilarityTransform alignment;  // maps estimate positions onto ground truth
  std::vector<double> stamps;     // ground-truth stamp of each matched pose
  std::vector<Eigen::Vector3d> reference_positions;
  std::vector<Eigen::Vector3d> aligned_estimate_positions;
  std::vector<double> errors;  // m, one per matched pose
  ErrorStatistics statistics;
};

// Throws depot::Error naming the estimate when the alignment is impossible.
AteResult compute_ate(const MatchedTrajectories& matched, const AteOptions& options = {});

}  // namespace depot::eval
