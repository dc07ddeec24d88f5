#include "eval/maps_ate.h"

#include <map>

#include "common/error.h"
#include "eval/ate.h"
#include "eval/matched_trajectories.h"

namespace depot::eval {

MapsAte compute_maps_ate(const std::vector<StampedPose>& reference,
                         const std::vector<StampedPose>& atlas, const std::vector<int>& map_of_pose,
                         size_t frames_given, const AssociationOptions& association,
                         AlignmentKind alignment, const std::string& reference_name,
                         const std::string& estimate_name) {
  if (atlas.size() != map_of_pose.size())
    fail(estimate_name, "holds " + std::to_string(atlas.size()) + " poses, but the states name " +
                            std::to_string(map_of_pose.size()) + " frames with a pose");
  std::map<int, std::vector<StampedPose>> by_map;
  for (size_t i = 0; i < atlas.size(); ++i) by_map[map_of_pose[i]].push_back(atlas[i]);
  if (!by_map.count(0)) fail(estimate_name, "has no pose in map 0 (the trajectory's)");
  MapsAte out;
  out.frames_given = frames_given;
  out.maps = by_map.size();
  std::vector<double> errors;
  for (const auto& [map, poses] : by_map) {
    const std::string name = estimate_name + " (map " + std::to_string(map) + ")";
    AteResult ate;
    try {
      ate = compute_ate(match_trajectories(reference, poses, association, reference_name, name),
                        AteOptions{alignment});
    } catch (const Error&) {
      // Too few matched poses, or all in one place: a small map cannot be
      // aligned, and is counted as left out. The main map must be.
      if (map == 0) throw;
      ++out.maps_left_out;
      out.poses_left_out += poses.size();
      continue;
    }
    errors.insert(errors.end(), ate.errors.begin(), ate.errors.end());
    out.posed += ate.errors.size();
    if (map == 0) out.in_main_map = ate.errors.size();
  }
  out.posed += out.poses_left_out;
  out.statistics = compute_statistics(errors);
  return out;
}

}  // namespace depot::eval
