#pragma once
// From a skeleton's globals to the world poses of the mocap bodies a skin
// hangs from: what HumanRig and ClipRig share.
#include <vector>

#include <Eigen/Geometry>

#include "common/pose.h"

namespace depot::sim {

// A bone's rigid pose from its global transform: mocap bodies cannot scale,
// so any scale the file's nodes carry is dropped.
Pose rigid_bone_pose(const Eigen::Affine3d& global);

// World poses of `bones` (indices into `globals`) with the model frame at
// `root`, the model scaled by `scale` about its origin (the skin's vertices
// and bind poses are scaled alike, skinned_actor_xml.h).
void world_bone_poses(const std::vector<Eigen::Affine3d>& globals, const std::vector<int>& bones,
                      const Pose& root, double scale, std::vector<Pose>& world);

}  // namespace depot::sim
