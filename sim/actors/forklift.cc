#include "sim/actors/forklift.h"

#include "sim/actors/limb.h"

namespace depot::sim {
namespace {

constexpr double kForkHalfLength = 0.55, kForkHalfThickness = 0.025;

}  // namespace

ForkliftActor::ForkliftActor(const ActorSpec& spec) {
  name_ = spec.name;
  class_name_ = "forklift";
  carry_ = std::make_shared<CarryMotion>(spec, actor_path(spec), 1.0);
  using V3 = Eigen::Vector3d;
  auto add = [&](const std::string& name, Shape shape, const V3& half, const V3& at,
                 const std::string& material) {
    parts_.push_back({name, shape, half, material, false});
    local_.push_back(make_pose(Eigen::Matrix3d::Identity(), at));
  };
  // x forward (the forks' side), origin on the floor under the front axle.
  add("chassis", Shape::kBox, V3(0.55, 0.45, 0.3), V3(-0.35, 0, 0.45), "rack_paint");
  add("counterweight", Shape::kBox, V3(0.18, 0.45, 0.35), V3(-1.0, 0, 0.5), "dark_metal");
  add("seat", Shape::kBox, V3(0.2, 0.22, 0.12), V3(-0.5, 0, 0.87), "chair_fabric");
  for (double side : {-1.0, 1.0}) {
    add(side < 0 ? "pillar_front_r" : "pillar_front_l", Shape::kBox, V3(0.03, 0.03, 0.65),
        V3(0.05, side * 0.42, 1.4), "dark_metal");
    add(side < 0 ? "pillar_back_r" : "pillar_back_l", Shape::kBox, V3(0.03, 0.03, 0.65),
        V3(-0.85, side * 0.42, 1.4), "dark_metal");
    add(side < 0 ? "mast_r" : "mast_l", Shape::kBox, V3(0.04, 0.04, 1.05),
        V3(0.3, side * 0.32, 1.1), "dark_metal");
    add(side < 0 ? "wheel_front_r" : "wheel_front_l", Shape::kBox, V3(0.17, 0.08, 0.17),
        V3(0.0, side * 0.5, 0.17), "dark_metal");
    add(side < 0 ? "wheel_back_r" : "wheel_back_l", Shape::kBox, V3(0.14, 0.08, 0.14),
        V3(-0.85, side * 0.5, 0.14), "dark_metal");
  }
  add("guard", Shape::kBox, V3(0.5, 0.45, 0.025), V3(-0.4, 0, 2.05), "dark_metal");
  first_fork_ = parts_.size();
  for (double side : {-1.0, 1.0})
    add(side < 0 ? "fork_r" : "fork_l", Shape::kBox, V3(kForkHalfLength, 0.05, kForkHalfThickness),
        V3(0.9, side * 0.22, 0.1), "dark_metal");
}

Pose ForkliftActor::root_pose(double t) const {
  return carry_->carrier_root(t);
}

std::unique_ptr<Actor> ForkliftActor::make_carried_goods() const {
  return std::make_unique<CarriedGoods>(name_, carry_);
}

void ForkliftActor::pose_parts(double t, std::vector<Pose>& world_poses) const {
  const Pose root = root_pose(t);
  // The forks under the pallet's deck wherever it rides.
  const Eigen::Vector3d goods = carry_->goods_in_carrier(t).translation();
  const double fork_z = goods.z() - carry_->goods_half().z() - kForkHalfThickness;
  world_poses.resize(parts_.size());
  for (size_t i = 0; i < parts_.size(); ++i) {
    Pose local = local_[i];
    if (i >= first_fork_) local.translation().z() = fork_z;
    world_poses[i] = root * local;
  }
}

Eigen::AlignedBox3d ForkliftActor::local_extent() const {
  Eigen::AlignedBox3d box = parts_extent(parts_, local_);
  box.extend(Eigen::Vector3d(0.9 + kForkHalfLength, 0, 0.6));  // the forks at their highest
  return box;
}

}  // namespace depot::sim
