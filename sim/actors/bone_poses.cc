#include "sim/actors/bone_poses.h"

namespace depot::sim {

Pose rigid_bone_pose(const Eigen::Affine3d& global) {
  Pose p = Pose::Identity();
  p.linear() = Eigen::Quaterniond(global.linear()).normalized().toRotationMatrix();
  p.translation() = global.translation();
  return p;
}

void world_bone_poses(const std::vector<Eigen::Affine3d>& globals, const std::vector<int>& bones,
                      const Pose& root, double scale, std::vector<Pose>& world) {
  world.resize(bones.size());
  for (size_t i = 0; i < bones.size(); ++i) {
    Pose local = rigid_bone_pose(globals[bones[i]]);
    local.translation() *= scale;
    world[i] = root * local;
  }
}

}  // namespace depot::sim
