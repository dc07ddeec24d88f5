#pragma once
#include <memory>

#include "sim/actors/actor.h"
#include "sim/actors/carry.h"
#include "sim/actors/human_rig.h"
#include "sim/scenario/path.h"

namespace depot::sim {

// A person of rigid parts with an articulated gait (legs and arms swing, the
// pelvis rides on the stance leg so the torso bobs). Walks a path, pushes a
// chair/cart with an invisible contact plate in front, sits on a chair
// moving head and arms slightly, carries goods back and forth (carry.h), or
// walks a crowd's simulated track (crowd.h).
class HumanActor : public Actor {
 public:
  HumanActor(const ActorSpec& spec, const SeatPose* seat);
  void pose_parts(double t, std::vector<Pose>& world_poses) const override;
  Pose root_pose(double t) const override;
  Eigen::AlignedBox3d local_extent() const override;
  void pose_bones(double t, std::vector<Pose>& world_poses) const override;

  // Draws this person as a skinned catalogue model instead of primitives:
  // the primitive parts stay (as geom-less mocap bodies, and the pusher
  // plate) and the rig's bones follow the same gait.
  void use_mesh(std::shared_ptr<const HumanRig> rig) { rig_ = std::move(rig); }
  const HumanRig* rig() const { return rig_.get(); }

  // The goods a carrier carries, as their own instance (nullptr for others).
  std::unique_ptr<Actor> make_carried_goods() const override;

  // The gait at time t (what both the primitives and the rig follow).
  HumanPosture posture(double t) const;

  // The invisible push plate in the root frame of a person of `scale`:
  // centre and half extents.
  static Eigen::Vector3d push_plate_centre(double scale);
  static Eigen::Vector3d push_plate_half(double scale);
  // The largest size factor an appearance gives (size x 0.92..1.07).
  static constexpr double kLargestScale = 1.07;

 private:
  enum class Mode { kWalk, kPush, kSit, kCarry, kCrowd };
  double distance(double t) const;

  Mode mode_ = Mode::kWalk;
  Path2D path_;
  double speed_ = 1.1;
  double offset_ = 0.0;
  double start_time_ = 0.0;
  double scale_ = 1.0;
  double phase_ = 0.0;       // per-person offset of idle motions
  double gait_phase_ = 0.0;  // rad, walking cycle at the start
  SeatPose seat_;
  std::shared_ptr<const CarryMotion> carry_;  // kCarry only
  std::vector<TrackPoint> track_;             // kCrowd only
  std::shared_ptr<const HumanRig> rig_;
};

}  // namespace depot::sim
