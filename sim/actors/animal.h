#pragma once
#include <memory>

#include "sim/actors/actor.h"
#include "sim/actors/clip_rig.h"
#include "sim/scenario/path.h"

namespace depot::sim {

// Four-legged animals (dog, cat, pig): a body, head, four legs in a trotting
// gait and a wagging tail, walking a path.
class QuadrupedActor : public Actor {
 public:
  explicit QuadrupedActor(const ActorSpec& spec);
  void pose_parts(double t, std::vector<Pose>& world_poses) const override;
  Pose root_pose(double t) const override;
  Eigen::AlignedBox3d local_extent() const override;
  void pose_bones(double t, std::vector<Pose>& world_poses) const override;

  // Draws this animal as a skinned catalogue model walking the same path
  // (its parts stay as geom-less mocap bodies). The model keeps the
  // catalogue's size: the actor's size factor applies to primitives only.
  void use_mesh(std::shared_ptr<const ClipRig> rig) { rig_ = std::move(rig); }

 private:
  struct Build {
    double body_half_length, body_radius, body_height, leg_length, leg_radius, head_radius, stride,
        tail_length;
  };
  double distance(double t) const;
  Build b_{};
  Path2D path_;
  double speed_ = 1.0, offset_ = 0.0, start_time_ = 0.0, scale_ = 1.0, gait_phase_ = 0.0;
  std::shared_ptr<const ClipRig> rig_;
};

// A bird flying a path at some height with flapping wings.
class BirdActor : public Actor {
 public:
  explicit BirdActor(const ActorSpec& spec);
  void pose_parts(double t, std::vector<Pose>& world_poses) const override;
  Pose root_pose(double t) const override;
  Eigen::AlignedBox3d local_extent() const override;
  void pose_bones(double t, std::vector<Pose>& world_poses) const override;

  // Draws this bird as a skinned catalogue model flapping with its clip.
  void use_mesh(std::shared_ptr<const ClipRig> rig) { rig_ = std::move(rig); }

 private:
  Path2D path_;
  double speed_ = 2.0, offset_ = 0.0, start_time_ = 0.0, scale_ = 1.0, height_ = 1.6, phase_ = 0.0;
  std::shared_ptr<const ClipRig> rig_;
};

}  // namespace depot::sim
