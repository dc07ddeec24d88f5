#include "eval/ate.h"

#include "common/error.h"

namespace depot::eval {
namespace {

std::vector<Eigen::Vector3d> positions_of(const std::vector<Pose>& poses) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(poses.size());
  for (const Pose& p : poses) out.push_back(p.translation());
  return out;
}

}  // namespace

AteResult compute_ate(const MatchedTrajectories& matched, const AteOptions& options) {
  if (matched.size() < kMinMatchedPairs) {
    fail(matched.estimate_name, "only " + std::to_string(matched.size()) +
                                    " matched poses, need at least " +
                                    std::to_string(kMinMatchedPairs));
  }
  AteResult out;
  out.alignment_kind = options.alignment;
  out.stamps = matched.reference_stamps;
  out.reference_positions = positions_of(matched.reference);
  const std::vector<Eigen::Vector3d> estimate = positions_of(matched.estimate);
  try {
    out.alignment = align_points(estimate, out.reference_positions, options.alignment);
  } catch (const Error& e) {
    fail(matched.estimate_name, e.what());
  }

  out.aligned_estimate_positions.reserve(estimate.size());
  out.errors.reserve(estimate.size());
  for (size_t k = 0; k < estimate.size(); ++k) {
    const Eigen::Vector3d aligned = out.alignment.apply(estimate[k]);
    out.aligned_estimate_positions.push_back(aligned);
    out.errors.push_back((out.reference_positions[k] - aligned).norm());
  }
  out.statistics = compute_statistics(out.errors);
  return out;
}

}  // namespace depot::eval
