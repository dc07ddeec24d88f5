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
// `root`.
void world_bone_poses(const std::vector<Eigen::Affine3d>& globals, const std::vector<int>& bones,
                      const Pose& root, std::vector<Pose>& world);

}  // namespace depot::sim
