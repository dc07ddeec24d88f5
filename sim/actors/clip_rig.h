#pragma once
// An animal drawn as a skinned catalogue model (assets/catalog.yaml): its
// bones posed from the file's own clips (a walk clip advanced by the
// distance walked, an idle clip when standing, a flap clip in the air), or,
// for a model without a walk clip, from its idle clip with the legs swung
// procedurally in a trot. Like HumanRig, each deforming bone is one mocap
// body a <skin> hangs from (sim/scene/skinned_actor_xml.h).
#include <memory>
#include <string>
#include <vector>

#include "common/pose.h"
#include "sim/assets/asset_catalog.h"
#include "sim/assets/asset_model.h"
#include "sim/assets/skinning.h"

namespace depot::sim {

// What the animal does at an instant.
struct AnimalMotion {
  // Walking: the gait cycle's phase (cycles; the fraction is what counts).
  // Standing or flying: the time (s) that drives the idle or flap clip.
  bool walking = false;
  double cycles = 0.0;
  double time = 0.0;
};

class ClipRig {
 public:
  enum class Gait { kWalk, kFly };
  // Fails naming the catalogue entry when a walking model has neither a walk
  // clip nor procedural legs, or no stride, or a flying model has no flap
  // clip, or a leg bone is missing.
  ClipRig(std::shared_ptr<const AssetModel> model, const CatalogAsset& entry, Gait gait);

  const AssetModel& model() const { return *model_; }
  // Bones that deform vertices, in skeleton order: one mocap body each.
  const std::vector<int>& body_bones() const { return body_bones_; }
  // Metres of ground per gait cycle.
  double stride() const { return stride_; }

  // Skeleton globals (model frame) for a motion.
  void globals(const AnimalMotion& m, std::vector<Eigen::Affine3d>& out) const;
  // World poses of body_bones() with the model frame at `root`, the model
  // scaled by `scale`.
  void pose(const AnimalMotion& m, const Pose& root, double scale, std::vector<Pose>& world) const;

 private:
  struct Leg {
    int hip = -1;
    int foot = -1;  // a carried IK foot, or -1
  };
  void swing_legs(double cycles, SkeletonPose& pose) const;

  std::shared_ptr<const AssetModel> model_;
  std::vector<int> body_bones_;
  int walk_ = -1, idle_ = -1, flap_ = -1;  // clip indices, -1 when absent
  double stride_ = 1.0;
  std::vector<Leg> legs_;              // procedural trot when there is no walk clip
  std::vector<Eigen::Affine3d> rest_;  // rest-pose globals, for carrying the legs' IK feet
};

}  // namespace depot::sim
