#pragma once
// Posing a loaded model's skeleton: a skeleton pose (local transforms of
// every bone), from a clip sampled at a time or from the simulator's own gait
// setting named bones, and the bones' global transforms.
//
// The meshes are skinned by MuJoCo, not here: sim/actors/human_rig.h and
// clip_rig.h pose the skeleton each step, sim/actors/bone_poses.h turns the
// globals into one mocap body per deforming bone, sim/scene/skinned_actor_xml.h
// binds each material submesh to those bodies as a `<skin>`, and MuJoCo
// blends the vertices when it renders. A CPU linear blend skinning that tests
// compare against is sim/assets/testing/cpu_skinning.h.
//
// Typical frame:
//   SkeletonPose pose = rest_pose(model.skeleton);
//   sample_clip(model.clips[walk], t, /*loop=*/true, pose);   // or turn_bone(...)
//   bone_globals(model.skeleton, pose, globals);
#include <string>
#include <vector>

#include "sim/assets/asset_model.h"

namespace depot::sim {

// Local translation, rotation and scale of every bone (same order as
// Skeleton::bones).
struct SkeletonPose {
  std::vector<Eigen::Vector3d> translation;
  std::vector<Eigen::Quaterniond> rotation;
  std::vector<Eigen::Vector3d> scale;
};

SkeletonPose rest_pose(const Skeleton& skeleton);

// Sets every bone the clip animates to its value at time t (s): keys are
// interpolated linearly (translation, scale) and by slerp (rotation). With
// `loop`, t wraps into [0, duration); otherwise it is clamped. Parts of a
// bone without keys, and bones the clip does not animate, are left as they
// are in `pose`.
void sample_clip(const AnimationClip& clip, double t, bool loop, SkeletonPose& pose);

// Global transforms of every bone in the model frame (root * parent chain).
void bone_globals(const Skeleton& skeleton, const SkeletonPose& pose,
                  std::vector<Eigen::Affine3d>& globals);

// Driving bones by name from the simulator's gait (the people's only clip is
// a short test walk).
//
// Index of every bone in `names`; fails naming `where` for a name the
// skeleton lacks.
std::vector<int> find_bones(const Skeleton& skeleton, const std::vector<std::string>& names,
                            const std::string& where);

// Sets the local rotation of a bone (relative to its parent, as clips do).
void set_bone_rotation(SkeletonPose& pose, int bone, const Eigen::Quaterniond& local);

// Turns a bone by `turn`, a rotation about its joint written in the model
// frame of the rest pose: with the parent at rest the bone and everything it
// carries rotate by `turn` about the joint, and the parent's own motion still
// carries the result. E.g. AngleAxis(-pitch, UnitY()) swings a thigh forward
// (toward +x) by `pitch`, like limb() in sim/actors/limb.h. The turn is
// relative to the rest pose, not accumulated.
void turn_bone(const Skeleton& skeleton, SkeletonPose& pose, int bone,
               const Eigen::Quaterniond& turn);

// Indices of the bones some vertex is weighted to (Bone::deforms), in
// skeleton order: the bones a skin hangs from.
std::vector<int> deforming_bones(const Skeleton& skeleton);

// Where a bone's joint is at the rest pose (model frame).
Eigen::Vector3d rest_joint_position(const Skeleton& skeleton, int bone);

}  // namespace depot::sim
