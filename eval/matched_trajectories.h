#pragma once
// A ground-truth trajectory and an estimate reduced to the poses that share a
// timestamp (see association.h): element k of both pose lists belongs to the
// same instant. This is what ATE and RPE are computed on.
#include <string>
#include <vector>

#include "common/pose.h"
#include "common/tum_association.h"
#include "common/tum_io.h"

namespace depot::eval {

// Fewer matched pairs than this cannot be aligned meaningfully.
inline constexpr size_t kMinMatchedPairs = 3;

struct MatchedTrajectories {
  std::string reference_name;  // usually the ground-truth file path
  std::string estimate_name;   // usually the estimate file path
  size_t reference_size = 0;   // poses before matching
  size_t estimate_size = 0;
  AssociationOptions association;
  std::vector<double> reference_stamps;  // ascending
  std::vector<double> estimate_stamps;
  std::vector<Pose> reference;
  std::vector<Pose> estimate;

  size_t size() const { return reference.size(); }
};

// Associates the two trajectories by timestamp. Throws depot::Error naming
// the estimate when the time ranges do not overlap or fewer than
// kMinMatchedPairs poses match.
MatchedTrajectories match_trajectories(const std::vector<StampedPose>& reference,
                                       const std::vector<StampedPose>& estimate,
                                       const AssociationOptions& options,
                                       const std::string& reference_name,
                                       const std::string& estimate_name);

// Reads two TUM trajectory files and matches them.
MatchedTrajectories load_matched_trajectories(const std::string& reference_path,
                                              const std::string& estimate_path,
                                              const AssociationOptions& options = {});

}  // namespace depot::eval
