#pragma once
// A hinged door that swings open and shut (`doors:` in a scenario): one leaf
// turning about a vertical hinge by `swing_deg` x its share open. The share
// follows the door's `events`, or a seeded timeline: shut for a time drawn in
// `shut`, a swing of kDoorSwing s, open for one drawn in `open`, a swing back,
// and again. Class `door` (a-priori static); its truth flags it moving exactly
// while it swings.
#include <cstdint>
#include <vector>

#include "sim/actors/actor.h"

namespace depot::sim {

constexpr double kDoorSwing = 1.5;  // s, for a seeded door's swing

class DoorActor : public Actor {
 public:
  DoorActor(const DoorSpec& spec, uint64_t world_seed);
  // 0 = shut, 1 = open by swing_deg.
  double share_open(double t) const;
  void pose_parts(double t, std::vector<Pose>& world_poses) const override;
  // The hinge frame: x along the leaf, z up.
  Pose root_pose(double t) const override;
  Eigen::AlignedBox3d local_extent() const override;

 private:
  DoorSpec spec_;
  std::vector<Eigen::Vector2d> events_;  // [time, share], the seeded ones drawn
};

}  // namespace depot::sim
