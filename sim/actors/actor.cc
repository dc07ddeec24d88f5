#include "sim/actors/actor.h"

#include "common/error.h"
#include "sim/actors/animal.h"
#include "sim/actors/forklift.h"
#include "sim/actors/human.h"
#include "sim/actors/limb.h"

namespace depot::sim {

Pose ground_pose(const Eigen::Vector2d& xy, double z, double yaw) {
  return make_pose(rot_z(yaw), Eigen::Vector3d(xy.x(), xy.y(), z));
}

Eigen::AlignedBox3d parts_extent(const std::vector<BodyPart>& parts,
                                 const std::vector<Pose>& local) {
  Eigen::AlignedBox3d box;
  for (size_t i = 0; i < parts.size(); ++i) {
    box.extend(local[i].translation() - parts[i].size);
    box.extend(local[i].translation() + parts[i].size);
  }
  return box;
}

Path2D actor_path(const ActorSpec& spec) {
  return Path2D(spec.path, spec.loop, spec.type == "bird" ? 0.8 : 0.5, spec.lane);
}

std::unique_ptr<Actor> make_actor(const ActorSpec& spec, const SeatPose* seat) {
  if (spec.type == "human") return std::make_unique<HumanActor>(spec, seat);
  if (spec.type == "dog" || spec.type == "cat" || spec.type == "pig")
    return std::make_unique<QuadrupedActor>(spec);
  if (spec.type == "bird") return std::make_unique<BirdActor>(spec);
  if (spec.type == "forklift") return std::make_unique<ForkliftActor>(spec);
  fail(spec.name, "not an animated actor type: '" + spec.type + "'");
}

}  // namespace depot::sim
