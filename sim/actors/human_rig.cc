#include "sim/actors/human_rig.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "sim/actors/bone_poses.h"

namespace depot::sim {
namespace {

enum Drive {
  kPelvis,
  kSpine,
  kNeck,
  kHead,
  kThighL,
  kCalfL,
  kFootL,
  kThighR,
  kCalfR,
  kFootR,
  kUpperArmL,
  kLowerArmL,
  kUpperArmR,
  kLowerArmR
};

Eigen::Quaterniond about_y(double a) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(a, Eigen::Vector3d::UnitY()));
}
Eigen::Quaterniond about_x(double a) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(a, Eigen::Vector3d::UnitX()));
}
Eigen::Quaterniond about_z(double a) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()));
}

}  // namespace

HumanRig::HumanRig(std::shared_ptr<const AssetModel> model) : model_(std::move(model)) {
  const Skeleton& sk = model_->skeleton;
  drive_ =
      find_bones(sk,
                 {"pelvis", "spine_01", "neck_01", "head", "thigh_l", "calf_l", "foot_l", "thigh_r",
                  "calf_r", "foot_r", "upperarm_l", "lowerarm_l", "upperarm_r", "lowerarm_r"},
                 model_->source);
  body_bones_ = deforming_bones(sk);
  const Eigen::Vector3d hip = rest_joint_position(sk, drive_[kThighL]);
  const Eigen::Vector3d knee = rest_joint_position(sk, drive_[kCalfL]);
  const Eigen::Vector3d ankle = rest_joint_position(sk, drive_[kFootL]);
  thigh_length_ = (knee - hip).norm();
  calf_length_ = (ankle - knee).norm();
  hip_height_ = hip.z();
  // MakeHuman binds in an A-pose; the gait's arms hang straight down first.
  for (int i = 0; i < 2; ++i) {
    const Eigen::Vector3d shoulder = rest_joint_position(sk, drive_[kUpperArmL + 2 * i]);
    const Eigen::Vector3d elbow = rest_joint_position(sk, drive_[kLowerArmL + 2 * i]);
    arm_drop_[i] = std::atan2(std::abs(elbow.y() - shoulder.y()), shoulder.z() - elbow.z());
  }
}

void HumanRig::globals(const HumanPosture& p, std::vector<Eigen::Affine3d>& out) const {
  const Skeleton& sk = model_->skeleton;
  SkeletonPose pose = rest_pose(sk);
  // Turns are relative to the rest pose about each joint, in the model frame
  // (turn_bone); a parent's turn carries its children, so each bone gets the
  // angle relative to its parent, as limb() composes them.
  turn_bone(sk, pose, drive_[kPelvis], about_z(0.5 * p.torso_yaw));
  turn_bone(sk, pose, drive_[kSpine], about_z(0.5 * p.torso_yaw) * about_y(p.torso_pitch));
  turn_bone(sk, pose, drive_[kHead], about_z(p.head_yaw) * about_y(p.head_pitch));
  for (int i = 0; i < 2; ++i) {
    const double side = i == 0 ? 1.0 : -1.0;
    turn_bone(sk, pose, drive_[kThighL + 3 * i], about_y(-p.hip[i]));
    turn_bone(sk, pose, drive_[kCalfL + 3 * i], about_y(p.knee[i]));
    // Keep the foot level with the ground (the shin is pitched hip - knee).
    turn_bone(sk, pose, drive_[kFootL + 3 * i], about_y(p.hip[i] - p.knee[i]));
    // The upper arm first drops from the A-pose to hanging straight down,
    // then swings; the elbow's turn is written in that dropped frame so the
    // forearm bends forward, not out to the side.
    const Eigen::Quaterniond drop = about_x(-side * arm_drop_[i]);
    turn_bone(sk, pose, drive_[kUpperArmL + 2 * i], about_y(-p.shoulder[i]) * drop);
    turn_bone(sk, pose, drive_[kLowerArmL + 2 * i], drop.inverse() * about_y(-p.elbow[i]) * drop);
  }
  // The pelvis rides on the longer (stance) leg, like the primitive person's,
  // with this model's own leg lengths; seated, the hips rest on the seat.
  double dz = 0.0;
  if (p.seated) {
    dz = p.seat_height + 0.06 - hip_height_;
  } else {
    double reach = 0.0;
    for (int i = 0; i < 2; ++i)
      reach = std::max(reach, thigh_length_ * std::cos(p.hip[i]) +
                                  calf_length_ * std::cos(p.hip[i] - p.knee[i]));
    dz = reach - (thigh_length_ + calf_length_);
  }
  const int pelvis = drive_[kPelvis];
  if (sk.bones[pelvis].parent >= 0) {
    // Lift in the model frame: move the pelvis' own translation by the
    // parent's inverse (the Root/Armature nodes above it are static).
    std::vector<Eigen::Affine3d> rest;
    bone_globals(sk, pose, rest);
    const Eigen::Affine3d& parent = rest[sk.bones[pelvis].parent];
    pose.translation[pelvis] += parent.linear().inverse() * Eigen::Vector3d(0, 0, dz);
  } else {
    pose.translation[pelvis] += sk.root.linear().inverse() * Eigen::Vector3d(0, 0, dz);
  }
  bone_globals(sk, pose, out);
}

void HumanRig::pose(const HumanPosture& p, const Pose& root, double scale,
                    std::vector<Pose>& world) const {
  std::vector<Eigen::Affine3d> g;
  HumanPosture scaled = p;
  scaled.seat_height = p.seat_height / scale;  // in the unscaled model's metres
  globals(scaled, g);
  world_bone_poses(g, body_bones_, root, scale, world);
}

}  // namespace depot::sim
