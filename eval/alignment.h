#pragma once
// Closed-form least-squares alignment of two point sets (Umeyama 1991; the
// same solution as Horn's method used by TUM's evaluate_ate.py and evo's
// `-a` / `-as`): finds s, R, t minimising sum_k |s R x_k + t - y_k|^2, with
// s fixed to 1 for a rigid SE(3) fit.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "common/pose.h"

namespace depot::eval {

enum class AlignmentKind {
  kNone,        // compare as given
  kRigid,       // SE(3): rotation and translation (RGB-D default)
  kSimilarity,  // Sim(3): also a uniform scale (monocular)
};

std::string to_string(AlignmentKind kind);

// y = scale * rotation * x + translation
struct SimilarityTransform {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  double scale = 1.0;

  Eigen::Vector3d apply(const Eigen::Vector3d& x) const {
    return scale * (rotation * x) + translation;
  }
};

// The transform that maps `source` (the estimate) onto `target` (the ground
// truth). Both lists have the same length, at least one point. Throws
// depot::Error when a scale is asked for but the source points all coincide.
SimilarityTransform align_points(const std::vector<Eigen::Vector3d>& source,
                                 const std::vector<Eigen::Vector3d>& target, AlignmentKind kind);

// The rigid transform that maps the `source` poses (an estimate's world)
// onto the `target` poses (the truth's), using their orientations as well as
// their positions: the rotation is the chordal mean of R_target R_source^T
// (the rotation nearest to their sum), the translation the mean of
// t_target - R t_source. A trajectory that barely moves (a hand-held camera
// swaying 30 cm) pins its world's orientation through its poses, not its
// positions: what maps a map's points, metres away, into the truth's world.
SimilarityTransform align_poses(const std::vector<Pose>& source, const std::vector<Pose>& target);

}  // namespace depot::eval
