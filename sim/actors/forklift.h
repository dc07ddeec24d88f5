#pragma once
// A small forklift of primitive parts (chassis, counterweight, mast, overhead
// guard, wheels, forks) that carries a pallet with goods out and back along
// its path (`type: forklift, carries: pallet`): the carry timeline of
// carry.h, its forks under the pallet as it is lifted, carried and set down.
// Class `forklift` (a-priori dynamic, no detector class: COCO has none).
#include <memory>
#include <vector>

#include "sim/actors/actor.h"
#include "sim/actors/carry.h"

namespace depot::sim {

class ForkliftActor : public Actor {
 public:
  explicit ForkliftActor(const ActorSpec& spec);
  void pose_parts(double t, std::vector<Pose>& world_poses) const override;
  Pose root_pose(double t) const override;
  Eigen::AlignedBox3d local_extent() const override;
  std::unique_ptr<Actor> make_carried_goods() const override;

 private:
  std::shared_ptr<const CarryMotion> carry_;
  std::vector<Pose> local_;  // each part in the root frame (the forks move)
  size_t first_fork_ = 0;
};

}  // namespace depot::sim
