#pragma once
// Animated actors (humans, animals): rigid parts posed kinematically every
// physics step. Each part becomes one MuJoCo mocap body; all parts of an actor
// share one instance id in the labels.
#include <memory>
#include <string>
#include <vector>

#include "common/pose.h"
#include "sim/scenario/path.h"
#include "sim/scenario/scenario.h"

namespace depot::sim {

enum class Shape { kBox, kSphere, kCapsule, kEllipsoid, kCylinder };

struct BodyPart {
  std::string name;  // unique within the actor
  Shape shape = Shape::kBox;
  Eigen::Vector3d size{0.1, 0.1, 0.1};  // MuJoCo geom size (half extents; capsule: r, half-length)
  std::string material;                 // scene material name
  bool pusher = false;                  // invisible collision plate that pushes chairs/carts
};

class Actor {
 public:
  virtual ~Actor() = default;
  const std::string& name() const { return name_; }
  const std::string& class_name() const { return class_name_; }
  const std::vector<BodyPart>& parts() const { return parts_; }

  // World poses of all parts (same order as parts()) at time t (s since start).
  virtual void pose_parts(double t, std::vector<Pose>& world_poses) const = 0;
  // The actor's reference pose at time t (on the ground, x forward, z up).
  virtual Pose root_pose(double t) const = 0;
  // Axis-aligned extent of the actor in its root frame, for label checks.
  virtual Eigen::AlignedBox3d local_extent() const = 0;
  // World poses of the skinned model's bone bodies (mesh style; they follow
  // the parts' mocap bodies in the instance). None for primitive actors.
  virtual void pose_bones(double t, std::vector<Pose>& world_poses) const {
    (void)t;
    world_poses.clear();
  }
  // The goods a carrier carries, as an instance of their own (carry.h);
  // nullptr for actors that carry nothing.
  virtual std::unique_ptr<Actor> make_carried_goods() const { return nullptr; }
  // How much a skinned model is scaled about its model origin: the
  // scenario's size factor (dynamic load); the model's own height is its
  // appearance.
  double mesh_scale() const { return mesh_scale_; }

 protected:
  std::string name_;
  std::string class_name_;
  std::vector<BodyPart> parts_;
  double mesh_scale_ = 1.0;
};

// Where a sitting actor sits: the chair's initial ground pose.
struct SeatPose {
  Eigen::Vector2d position{0, 0};
  double yaw = 0.0;
  double seat_height = 0.46;
};

std::unique_ptr<Actor> make_actor(const ActorSpec& spec, const SeatPose* seat);

// The smoothed path a walking, flying or pushing actor follows (birds turn
// wider), including its lane offset.
Path2D actor_path(const ActorSpec& spec);

// The bounds of rigid parts placed at `local` poses (their centres; a part's
// size taken as half extents, unrotated), e.g. a vehicle's or a pallet's.
Eigen::AlignedBox3d parts_extent(const std::vector<BodyPart>& parts,
                                 const std::vector<Pose>& local);

// Root pose on the ground: position (x, y), heading yaw about +z.
Pose ground_pose(const Eigen::Vector2d& xy, double z, double yaw);

}  // namespace depot::sim
