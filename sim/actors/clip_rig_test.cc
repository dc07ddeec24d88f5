// The animals' rig: the walk clip advances with the distance walked (one
// stride is one cycle), and a model without a walk clip swings its legs
// procedurally, carrying its IK feet with the legs.
#include "sim/actors/clip_rig.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/config_path.h"
#include "common/error.h"
#include "sim/assets/skinning.h"

namespace depot::sim {
namespace {

const AssetCatalog& catalog() {
  static const ClassTable classes = ClassTable::load(project_file("scenes/classes.yaml"));
  static const AssetCatalog c = load_asset_catalog(project_file("assets/catalog.yaml"), classes);
  return c;
}

ClipRig rig_of(const std::string& name, ClipRig::Gait gait = ClipRig::Gait::kWalk) {
  const CatalogAsset& entry = catalog_asset(catalog(), name);
  return ClipRig(std::make_shared<const AssetModel>(load_catalog_asset(catalog(), entry)), entry,
                 gait);
}

Eigen::Vector3d bone_at(const ClipRig& rig, const AnimalMotion& m, const std::string& bone) {
  std::vector<Eigen::Affine3d> g;
  rig.globals(m, g);
  return g[find_bone(rig.model().skeleton, bone)].translation();
}

AnimalMotion walking(double cycles) {
  AnimalMotion m;
  m.walking = true;
  m.cycles = cycles;
  return m;
}

TEST(ClipRig, WalkClipIsPeriodicInStridesAndMovesTheFeet) {
  const ClipRig dog = rig_of("dog");
  EXPECT_DOUBLE_EQ(dog.stride(), 0.9);
  const std::string foot = "Front_Leg_Tip_L";
  // A whole cycle later the foot is back where it was.
  EXPECT_LT((bone_at(dog, walking(0.2), foot) - bone_at(dog, walking(1.2), foot)).norm(), 1e-6);
  // Half a cycle apart the front foot has moved a good part of a step.
  double reach = 0;
  for (double c = 0; c < 1.0; c += 0.05)
    reach = std::max(
        reach, (bone_at(dog, walking(c), foot) - bone_at(dog, walking(c + 0.5), foot)).norm());
  EXPECT_GT(reach, 0.08) << "the walk clip must move the dog's feet";
}

TEST(ClipRig, ProceduralLegsSwingAndCarryTheirFeet) {
  const ClipRig pig = rig_of("pig");
  const Skeleton& sk = pig.model().skeleton;
  const Eigen::Vector3d hip = rest_joint_position(sk, find_bone(sk, "FrontUpLeg.L"));
  // A quarter cycle: the front left leg is swung fully forward, the front
  // right fully back (trot: diagonal pairs together).
  const Eigen::Vector3d fl = bone_at(pig, walking(0.25), "FrontFoot.L");
  const Eigen::Vector3d fr = bone_at(pig, walking(0.25), "FrontFoot.R");
  const Eigen::Vector3d rest_fl = rest_joint_position(sk, find_bone(sk, "FrontFoot.L"));
  EXPECT_GT(fl.x() - rest_fl.x(), 0.1) << "the carried foot moves forward with its leg";
  EXPECT_LT(fr.x() - rest_fl.x(), -0.1);
  // The carried foot stays at its rest distance from the hip: it moved with
  // the leg, not on its own.
  EXPECT_NEAR((fl - hip).norm(), (rest_fl - hip).norm(), 0.05);
  // The lower leg (a child of the swung bone) goes the same way.
  EXPECT_GT(bone_at(pig, walking(0.25), "FrontLowLeg.L").x(),
            rest_joint_position(sk, find_bone(sk, "FrontLowLeg.L")).x() + 0.03);
}

TEST(ClipRig, FlyingBirdFlapsWithItsClip) {
  const ClipRig gull = rig_of("seagull", ClipRig::Gait::kFly);
  AnimalMotion a, b;
  a.time = 0.0;
  b.time = 0.3 * gull.model().clips[find_clip(gull.model(), "Flap")].duration;
  EXPECT_GT((bone_at(gull, a, "wing_4_L") - bone_at(gull, b, "wing_4_L")).norm(), 0.03);
}

TEST(ClipRig, AnimalWithoutWalkOrLegsFailsNamingTheAsset) {
  CatalogAsset entry = catalog_asset(catalog(), "sheep");  // Idle and Jump only
  entry.stride = 0.7;
  const auto model = std::make_shared<const AssetModel>(load_catalog_asset(catalog(), entry));
  try {
    ClipRig rig(model, entry, ClipRig::Gait::kWalk);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_THAT(std::string(e.what()), ::testing::HasSubstr("asset 'sheep'")) << e.what();
    EXPECT_THAT(std::string(e.what()), ::testing::HasSubstr("walk")) << e.what();
  }
}

}  // namespace
}  // namespace depot::sim
