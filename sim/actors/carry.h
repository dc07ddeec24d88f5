#pragma once
// A person carrying goods (a crate or a sack), or a forklift carrying a
// pallet with goods, back and forth along an open path: scenario actors with
// `carries: crate|sack|pallet` (human.h, forklift.h; action carry).
//
// The goods rest in front of the carrier at the path's start (on a support
// `pick_height` m up: a pallet, a shelf, or the floor). From `start_time`
// the carrier bends and lifts them (kLift s), walks to the path's end with
// them held in front at the waist, bends and sets them down there
// (`put_height`), waits, lifts them again and carries them back, and so on;
// each wait is drawn from the actor's seed. While resting the goods are
// still (their `moving` flag is false); lifted, carried or set down they
// move with the hands. Their class is their own (crate, sack: a-priori
// static), whatever they do.
#include <memory>
#include <string>

#include "common/pose.h"
#include "sim/actors/actor.h"
#include "sim/scenario/path.h"

namespace depot::sim {

constexpr double kLift = 1.2;  // s to lift or set down

// Where the carrier is and what it does with the goods at time t.
struct CarryState {
  double distance = 0.0;  // along the path walked out and back (Path2D, open)
  double lift = 0.0;      // 0 = resting on their support, 1 = held
  double bend = 0.0;      // 0 = upright, 1 = bent down to the support
};

// One carrier's timeline and geometry, shared by the person and the goods.
class CarryMotion {
 public:
  CarryMotion(const ActorSpec& carrier, Path2D path, double scale);

  CarryState at(double t) const;
  const Path2D& path() const { return path_; }
  Pose carrier_root(double t) const;
  // The goods' pose at t (their centre; x forward of the carrier, z up).
  Pose goods_pose(double t) const;
  const std::string& goods() const { return goods_; }
  // Half extents of the goods' base part (crate: a box; sack: an
  // ellipsoid; pallet: its deck, the crates on it come on top).
  Eigen::Vector3d goods_half() const;
  double scale() const { return scale_; }
  // The goods' pose in the carrier's root frame at t (what a forklift's
  // forks follow).
  Pose goods_in_carrier(double t) const;

 private:
  Pose root_at(double distance) const;  // the carrier on its path
  Pose rest_pose(double distance, double height) const;
  Pose held_pose(double distance) const;

  Path2D path_;
  std::string goods_;
  // Where the goods rest and are held, ahead of the carrier's root (m).
  double rest_ahead_ = 0.62, held_ahead_ = 0.40, held_height_ = 1.02;
  double speed_ = 1.0;
  double start_time_ = 0.0;
  double scale_ = 1.0;
  double pick_height_ = 0.0, put_height_ = 0.0;
  double wait_at_end_ = 1.0, wait_at_start_ = 1.0;  // s, drawn from the seed
};

// The goods as an animated instance (one rigid part) following CarryMotion.
class CarriedGoods : public Actor {
 public:
  CarriedGoods(const std::string& carrier_name, std::shared_ptr<const CarryMotion> motion);
  void pose_parts(double t, std::vector<Pose>& world_poses) const override;
  Pose root_pose(double t) const override;
  Eigen::AlignedBox3d local_extent() const override;

 private:
  std::shared_ptr<const CarryMotion> motion_;
  std::vector<Pose> local_;  // each part in the goods' frame
};

}  // namespace depot::sim
