#include "sim/actors/clip_rig.h"

#include <cmath>

#include "common/error.h"
#include "sim/actors/bone_poses.h"
#include "sim/assets/skinning.h"

namespace depot::sim {
namespace {

int clip_of(const AssetModel& model, const CatalogAsset& entry, const std::string& role) {
  auto it = entry.clips.find(role);
  return it == entry.clips.end() ? -1 : find_clip(model, it->second);
}

double fraction(double cycles) {
  return cycles - std::floor(cycles);
}

// A leg's swing (rad, forward positive) in a trot: diagonal legs together.
constexpr double kSwing = 0.45;
constexpr double kLegPhase[4] = {0.0, 0.5, 0.5, 0.0};  // FL, FR, BL, BR (cycles)

}  // namespace

ClipRig::ClipRig(std::shared_ptr<const AssetModel> model, const CatalogAsset& entry, Gait gait)
    : model_(std::move(model)) {
  const Skeleton& sk = model_->skeleton;
  const std::string where = "asset '" + entry.name + "' (" + model_->source + ")";
  body_bones_ = deforming_bones(sk);
  walk_ = clip_of(*model_, entry, "walk");
  idle_ = clip_of(*model_, entry, "idle");
  flap_ = clip_of(*model_, entry, "flap");
  if (gait == Gait::kFly) {
    if (flap_ < 0) fail(where, "a flying animal needs a 'flap' clip in the catalogue");
    walk_ = -1;
    return;
  }
  flap_ = -1;
  if (entry.stride > 0) stride_ = entry.stride;
  if (walk_ < 0 && !entry.legs.empty()) {
    for (const auto& names : entry.legs) {
      const std::vector<int> bones = find_bones(sk, names, where);
      legs_.push_back({bones[0], bones.size() > 1 ? bones[1] : -1});
    }
    bone_globals(sk, rest_pose(sk), rest_);
  }
  if (walk_ < 0 && legs_.empty())
    fail(where, "a walking animal needs a 'walk' clip or procedural 'legs' in the catalogue");
  if (entry.stride <= 0)
    fail(where, "a walking animal needs 'stride' (metres per gait cycle) in the catalogue");
}

void ClipRig::swing_legs(double cycles, SkeletonPose& pose) const {
  const Skeleton& sk = model_->skeleton;
  const std::vector<Eigen::Affine3d>& rest = rest_;
  for (size_t i = 0; i < legs_.size(); ++i) {
    const double a = kSwing * std::sin(2.0 * M_PI * (cycles + kLegPhase[i % 4]));
    // Forward swing turns the leg about -y (x forward, z up), as in limb().
    const Eigen::Quaterniond turn(Eigen::AngleAxisd(-a, Eigen::Vector3d::UnitY()));
    turn_bone(sk, pose, legs_[i].hip, turn);
    const int foot = legs_[i].foot;
    if (foot < 0) continue;
    // The IK foot hangs from the root, not from the leg: move it as the leg
    // moves it, a turn about the hip joint, lifted while the leg swings
    // forward.
    const Eigen::Vector3d hip = rest_joint_position(sk, legs_[i].hip);
    const double lift =
        0.06 * hip.z() * std::max(0.0, std::cos(2.0 * M_PI * (cycles + kLegPhase[i % 4])));
    Eigen::Affine3d moved = Eigen::Translation3d(hip + Eigen::Vector3d(0, 0, lift)) * turn *
                            Eigen::Translation3d(-hip) * rest[foot];
    const Eigen::Affine3d parent =
        sk.bones[foot].parent >= 0 ? rest[sk.bones[foot].parent] : sk.root;
    const Eigen::Affine3d local = parent.inverse() * moved;
    pose.translation[foot] = local.translation();
    pose.rotation[foot] = Eigen::Quaterniond(local.linear()).normalized();
  }
}

void ClipRig::globals(const AnimalMotion& m, std::vector<Eigen::Affine3d>& out) const {
  const Skeleton& sk = model_->skeleton;
  SkeletonPose pose = rest_pose(sk);
  if (m.walking && walk_ >= 0) {
    const AnimationClip& walk = model_->clips[walk_];
    sample_clip(walk, fraction(m.cycles) * walk.duration, /*loop=*/true, pose);
  } else {
    const int clip = flap_ >= 0 ? flap_ : idle_;
    if (clip >= 0) sample_clip(model_->clips[clip], m.time, /*loop=*/true, pose);
    if (m.walking) swing_legs(m.cycles, pose);
  }
  bone_globals(sk, pose, out);
}

void ClipRig::pose(const AnimalMotion& m, const Pose& root, double scale,
                   std::vector<Pose>& world) const {
  std::vector<Eigen::Affine3d> g;
  globals(m, g);
  world_bone_poses(g, body_bones_, root, scale, world);
}

}  // namespace depot::sim
