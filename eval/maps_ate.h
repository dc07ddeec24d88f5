#pragma once
// ATE that counts every frame with a pose, in whichever map of the atlas it
// was tracked (slam/data/map.h): until maps merge, each has a coordinate
// frame of its own, so each is aligned to the ground truth on its own and
// one RMSE is taken over all of them. Beside it, what ATE over the
// trajectory alone hides: how many of the frames given have a pose at all,
// and the share the main map holds (the trajectory's frames).
#include <string>
#include <vector>

#include "common/tum_association.h"
#include "common/tum_io.h"
#include "eval/alignment.h"
#include "eval/statistics.h"

namespace depot::eval {

struct MapsAte {
  ErrorStatistics statistics;  // m, over every pose of the aligned maps
  size_t frames_given = 0;
  size_t posed = 0;           // frames with a pose in any map
  size_t in_main_map = 0;     // of them in map 0 (the trajectory)
  size_t maps = 0;            // maps with poses
  size_t maps_left_out = 0;   // maps too small (or degenerate) to align
  size_t poses_left_out = 0;  // their poses
  double posed_share() const { return frames_given ? double(posed) / frames_given : 0.0; }
  double main_map_share() const { return frames_given ? double(in_main_map) / frames_given : 0.0; }
};

// `atlas` holds every frame with a pose, each in its map's frame, and
// `map_of_pose` the map of each (0 = main). Poses without a ground-truth
// match are left out as ATE leaves them out. A map other than 0 with fewer
// than kMinMatchedPairs matched poses, or whose poses cannot be aligned, is
// counted in maps_left_out; map 0 must align. Throws depot::Error naming
// `estimate_name` when the lists differ in length or map 0 cannot be aligned.
MapsAte compute_maps_ate(const std::vector<StampedPose>& reference,
                         const std::vector<StampedPose>& atlas, const std::vector<int>& map_of_pose,
                         size_t frames_given, const AssociationOptions& association,
                         AlignmentKind alignment, const std::string& reference_name,
                         const std::string& estimate_name);

}  // namespace depot::eval
