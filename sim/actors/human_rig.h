#pragma once
// A MakeHuman skeleton (assets/catalog.yaml people) driven by the primitive
// person's gait: the same hip, knee, shoulder and elbow swings, torso and
// head turns and pelvis bob, turned into world poses of the deforming bones.
// Each deforming bone is one MuJoCo mocap body that a <skin> hangs from, so
// the GPU deforms the mesh and no per-frame mesh upload is needed.
#include <memory>
#include <vector>

#include "common/pose.h"
#include "sim/assets/asset_model.h"
#include "sim/assets/skinning.h"

namespace depot::sim {

// Joint angles of one instant (rad; index 0 = left, 1 = right), with the
// conventions of sim/actors/limb.h: a positive hip/shoulder swings the limb
// forward, a positive knee bends the shin back, a positive elbow bends the
// forearm forward.
struct HumanPosture {
  double hip[2] = {0, 0};
  double knee[2] = {0, 0};
  double shoulder[2] = {0, 0};
  double elbow[2] = {0, 0};
  double torso_pitch = 0, torso_yaw = 0;
  double head_yaw = 0, head_pitch = 0;
  bool seated = false;
  double seat_height = 0.46;  // m, when seated
};

class HumanRig {
 public:
  // Fails naming the model file when a bone the gait drives is missing.
  explicit HumanRig(std::shared_ptr<const AssetModel> model);

  const AssetModel& model() const { return *model_; }
  // Bones that deform vertices, in skeleton order: one mocap body each.
  const std::vector<int>& body_bones() const { return body_bones_; }

  // Skeleton globals (model frame, feet on z = 0 while walking) for a posture.
  void globals(const HumanPosture& p, std::vector<Eigen::Affine3d>& out) const;
  // World poses of body_bones() with the model frame at `root`, the model
  // scaled by `scale` (a seated person's hips still rest on the seat).
  void pose(const HumanPosture& p, const Pose& root, double scale, std::vector<Pose>& world) const;

 private:
  std::shared_ptr<const AssetModel> model_;
  std::vector<int> body_bones_;
  // pelvis, spine_01, neck_01, head, thigh/calf/foot l r, upperarm/lowerarm l r
  std::vector<int> drive_;
  double thigh_length_ = 0.45, calf_length_ = 0.45;
  double hip_height_ = 0.9;      // rest height of the hip joints
  double arm_drop_[2] = {0, 0};  // A-pose: upper arm's angle from straight down
};

}  // namespace depot::sim
