#include "sim/actors/carry.h"

#include <algorithm>
#include <cmath>

#include "common/rng.h"
#include "sim/actors/limb.h"

namespace depot::sim {
namespace {

// A pallet's deck and the two crates on it (half extents).
const Eigen::Vector3d kDeckHalf(0.6, 0.4, 0.07), kPalletCrateHalf(0.28, 0.2, 0.17);

double smooth(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3.0 - 2.0 * x);
}

}  // namespace

CarryMotion::CarryMotion(const ActorSpec& a, Path2D path, double scale)
    : path_(std::move(path)),
      goods_(a.carries),
      speed_(std::max(a.speed, 0.05)),
      start_time_(a.start_time),
      scale_(scale),
      pick_height_(a.pick_height),
      put_height_(a.put_height) {
  if (a.type == "forklift") {
    // The pallet rests just ahead of the forks' tips and rides 25 cm up.
    rest_ahead_ = held_ahead_ = 1.25;
    held_height_ = 0.25 + kDeckHalf.z();
  } else {
    // A person: goods on a support ahead, held at the waist closer in.
    rest_ahead_ = 0.62 * scale_;
    held_ahead_ = 0.40 * scale_;
    held_height_ = 1.02 * scale_;
  }
  Rng rng(derive_seed(a.appearance, 0x6361727279));
  wait_at_end_ = rng.uniform(0.5, 2.5);
  wait_at_start_ = rng.uniform(0.5, 2.5);
}

Eigen::Vector3d CarryMotion::goods_half() const {
  if (goods_ == "pallet") return kDeckHalf;
  return goods_ == "sack" ? Eigen::Vector3d(0.2, 0.3, 0.12) : Eigen::Vector3d(0.2, 0.22, 0.17);
}

CarryState CarryMotion::at(double t) const {
  // One cycle: lift, walk out, set down, wait, lift, walk back, set down, wait.
  const double half = 0.5 * path_.length();
  const double walk = half / speed_;
  const double cycle = 4 * kLift + 2 * walk + wait_at_end_ + wait_at_start_;
  CarryState s;
  double u = t - start_time_;
  if (u <= 0) return s;
  u = std::fmod(u, cycle);
  for (int leg = 0; leg < 2; ++leg) {
    const double from = leg * half;
    if (u < kLift) {  // lifting
      s.distance = from, s.lift = smooth(u / kLift), s.bend = std::sin(M_PI * u / kLift);
      return s;
    }
    u -= kLift;
    if (u < walk) {
      s.distance = from + speed_ * u, s.lift = 1.0;
      return s;
    }
    u -= walk;
    if (u < kLift) {  // setting down
      s.distance = from + half, s.lift = 1.0 - smooth(u / kLift);
      s.bend = std::sin(M_PI * u / kLift);
      return s;
    }
    u -= kLift;
    const double wait = leg == 0 ? wait_at_end_ : wait_at_start_;
    if (u < wait) {
      s.distance = from + half;
      return s;
    }
    u -= wait;
  }
  return s;  // (rounding at the cycle's end) back at the start
}

Pose CarryMotion::root_at(double distance) const {
  return ground_pose(path_.position(distance), 0.0, path_.heading(distance));
}

Pose CarryMotion::carrier_root(double t) const {
  return root_at(at(t).distance);
}

Pose CarryMotion::rest_pose(double distance, double height) const {
  return root_at(distance) * make_pose(Eigen::Matrix3d::Identity(),
                                       Eigen::Vector3d(rest_ahead_, 0, height + goods_half().z()));
}

Pose CarryMotion::held_pose(double distance) const {
  return root_at(distance) *
         make_pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(held_ahead_, 0, held_height_));
}

Pose CarryMotion::goods_pose(double t) const {
  const CarryState s = at(t);
  if (s.lift >= 1.0) return held_pose(s.distance);
  // Resting or on the way: they rest where the last leg ended. Before the
  // first lift and after a cycle that is the start; after the walk out, the
  // end. Which one: the half of the loop the carrier stands at.
  const double half = 0.5 * path_.length();
  const bool at_end = std::abs(s.distance - half) < 1e-9;
  const Pose rest = rest_pose(s.distance, at_end ? put_height_ : pick_height_);
  if (s.lift <= 0.0) return rest;
  const Pose held = held_pose(s.distance);
  return make_pose(rest.linear(), (1 - s.lift) * rest.translation() + s.lift * held.translation());
}

Pose CarryMotion::goods_in_carrier(double t) const {
  return carrier_root(t).inverse() * goods_pose(t);
}

CarriedGoods::CarriedGoods(const std::string& carrier_name,
                           std::shared_ptr<const CarryMotion> motion)
    : motion_(std::move(motion)) {
  name_ = carrier_name + "_" + motion_->goods();
  class_name_ = motion_->goods();
  const std::string& goods = motion_->goods();
  const Eigen::Vector3d half = motion_->goods_half();
  if (goods == "pallet") {
    parts_.push_back({"deck", Shape::kBox, half, "pallet", false});
    local_.push_back(Pose::Identity());
    for (double side : {-1.0, 1.0}) {
      parts_.push_back({side < 0 ? "crate_a" : "crate_b", Shape::kBox, kPalletCrateHalf,
                        side < 0 ? "crate" : "crate_dark", false});
      local_.push_back(make_pose(Eigen::Matrix3d::Identity(),
                                 Eigen::Vector3d(side * 0.3, 0, half.z() + kPalletCrateHalf.z())));
    }
  } else {
    const bool sack = goods == "sack";
    parts_.push_back(
        {"goods", sack ? Shape::kEllipsoid : Shape::kBox, half, sack ? "sack" : "crate", false});
    local_.push_back(Pose::Identity());
  }
}

void CarriedGoods::pose_parts(double t, std::vector<Pose>& world_poses) const {
  const Pose goods = motion_->goods_pose(t);
  world_poses.resize(local_.size());
  for (size_t i = 0; i < local_.size(); ++i) world_poses[i] = goods * local_[i];
}

Pose CarriedGoods::root_pose(double t) const {
  return motion_->goods_pose(t);
}

Eigen::AlignedBox3d CarriedGoods::local_extent() const {
  return parts_extent(parts_, local_);
}

}  // namespace depot::sim
