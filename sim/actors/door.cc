#include "sim/actors/door.h"

#include <algorithm>
#include <cmath>

#include "common/rng.h"
#include "sim/actors/actor_variation.h"
#include "sim/actors/limb.h"

namespace depot::sim {
namespace {

constexpr double kLeafHalfThickness = 0.025;  // m
constexpr double kSeededHorizon = 3600.0;     // s of seeded timeline drawn

}  // namespace

DoorActor::DoorActor(const DoorSpec& spec, uint64_t world_seed) : spec_(spec) {
  name_ = spec.name;
  class_name_ = "door";
  parts_.push_back({"leaf", Shape::kBox,
                    Eigen::Vector3d(spec.width / 2, kLeafHalfThickness, spec.height / 2), "door",
                    false});
  events_ = spec.events;
  if (events_.empty()) {
    Rng rng(derive_seed(world_seed, name_hash(spec.name), 0x646f6f72));
    double t = rng.uniform(spec.shut.x(), spec.shut.y());
    events_.emplace_back(0.0, 0.0);
    while (t < kSeededHorizon) {
      events_.emplace_back(t, 0.0);
      events_.emplace_back(t + kDoorSwing, 1.0);
      t += kDoorSwing + rng.uniform(spec.open.x(), spec.open.y());
      events_.emplace_back(t, 1.0);
      events_.emplace_back(t + kDoorSwing, 0.0);
      t += kDoorSwing + rng.uniform(spec.shut.x(), spec.shut.y());
    }
  }
}

double DoorActor::share_open(double t) const {
  if (t <= events_.front().x()) return events_.front().y();
  if (t >= events_.back().x()) return events_.back().y();
  const auto next = std::upper_bound(events_.begin(), events_.end(), t,
                                     [](double v, const Eigen::Vector2d& e) { return v < e.x(); });
  const Eigen::Vector2d& b = *next;
  const Eigen::Vector2d& a = *(next - 1);
  if (b.x() - a.x() < 1e-12) return b.y();  // a switch
  return a.y() + (b.y() - a.y()) * (t - a.x()) / (b.x() - a.x());
}

Pose DoorActor::root_pose(double t) const {
  const double angle = deg(spec_.yaw_deg + spec_.swing_deg * share_open(t));
  return ground_pose(spec_.hinge, 0.0, angle);
}

void DoorActor::pose_parts(double t, std::vector<Pose>& world_poses) const {
  world_poses.assign(
      1, root_pose(t) * make_pose(Eigen::Matrix3d::Identity(),
                                  Eigen::Vector3d(spec_.width / 2, 0, spec_.height / 2)));
}

Eigen::AlignedBox3d DoorActor::local_extent() const {
  return Eigen::AlignedBox3d(Eigen::Vector3d(0, -kLeafHalfThickness, 0),
                             Eigen::Vector3d(spec_.width, kLeafHalfThickness, spec_.height));
}

}  // namespace depot::sim
