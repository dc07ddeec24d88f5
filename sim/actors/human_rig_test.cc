// The skinned person's rig: a known gait posture puts the foot bone's mocap
// body where the leg's joint angles say, and the walking gait moves the
// bodies the way the primitive person's legs go.
#include "sim/actors/human_rig.h"

#include <gtest/gtest.h>

#include "sim/actors/human.h"
#include "sim/actors/limb.h"
#include "sim/assets/testing/asset_fixtures.h"

namespace depot::sim {
namespace {

std::shared_ptr<const HumanRig> worker_rig() {
  static const auto rig =
      std::make_shared<const HumanRig>(std::make_shared<const AssetModel>(testing::worker()));
  return rig;
}

// Index into body_bones() (= the actor's bone bodies) of a named bone.
size_t body_of(const HumanRig& rig, const std::string& bone) {
  const int b = find_bone(rig.model().skeleton, bone);
  for (size_t i = 0; i < rig.body_bones().size(); ++i)
    if (rig.body_bones()[i] == b) return i;
  ADD_FAILURE() << bone << " has no body";
  return 0;
}

TEST(HumanRig, KnownLegPostureMovesTheFootBodyWhereTheAnglesSay) {
  const HumanRig& rig = *worker_rig();
  const Skeleton& sk = rig.model().skeleton;
  const Eigen::Vector3d hip = rest_joint_position(sk, find_bone(sk, "thigh_l"));
  const Eigen::Vector3d knee = rest_joint_position(sk, find_bone(sk, "calf_l"));
  const Eigen::Vector3d ankle = rest_joint_position(sk, find_bone(sk, "foot_l"));
  // Left thigh 30 deg forward, knee bent 20 deg; the right leg stays straight,
  // so it is the stance leg and the pelvis does not move.
  HumanPosture p;
  p.hip[0] = deg(30.0);
  p.knee[0] = deg(20.0);
  const Pose root = ground_pose(Eigen::Vector2d(1.0, 2.0), 0.0, deg(90.0));
  std::vector<Pose> bodies;
  rig.pose(p, root, 1.0, bodies);
  ASSERT_EQ(bodies.size(), rig.body_bones().size());
  // A person of size 1.25 (dynamic load) is the same pose scaled about the
  // model's origin between the feet.
  std::vector<Pose> large;
  rig.pose(p, root, 1.25, large);
  for (size_t i = 0; i < bodies.size(); ++i)
    EXPECT_LT((root.inverse() * large[i].translation() -
               1.25 * (root.inverse() * bodies[i].translation()))
                  .norm(),
              1e-9);

  // The same chain as limb() in sim/actors/limb.h: pitch forward = rot_y(-pitch).
  const Eigen::Vector3d knee_now = hip + rot_y(-p.hip[0]) * (knee - hip);
  const Eigen::Vector3d ankle_now = knee_now + rot_y(-(p.hip[0] - p.knee[0])) * (ankle - knee);
  const Pose& foot = bodies[body_of(rig, "foot_l")];
  EXPECT_LT((foot.translation() - root * ankle_now).norm(), 1e-6);
  // Swung forward: in the world, forward is the root's +x (here world +y).
  EXPECT_GT((root.inverse() * foot.translation()).x() - ankle.x(), 0.15);
  // The foot is kept level: its orientation is the rest one, carried by the root.
  std::vector<Eigen::Affine3d> rest;
  bone_globals(sk, rest_pose(sk), rest);
  const Eigen::Quaterniond rest_q(rest[find_bone(sk, "foot_l")].linear());
  EXPECT_LT(Eigen::Quaterniond(foot.linear())
                .angularDistance(Eigen::Quaterniond(root.linear()) * rest_q.normalized()),
            1e-6);
  // The standing right foot has not moved.
  const Eigen::Vector3d right_ankle = rest_joint_position(sk, find_bone(sk, "foot_r"));
  EXPECT_LT((bodies[body_of(rig, "foot_r")].translation() - root * right_ankle).norm(), 1e-6);
}

TEST(HumanRig, WalkingActorSwingsItsFeetLikeTheGait) {
  ActorSpec spec;
  spec.name = "walker";
  spec.type = "human";
  spec.action = "walk";
  spec.path = {Eigen::Vector2d(0, 0), Eigen::Vector2d(20, 0)};
  spec.loop = false;
  spec.speed = 1.2;
  spec.appearance = 7;
  HumanActor actor(spec, nullptr);
  actor.use_mesh(worker_rig());
  const HumanRig& rig = *worker_rig();
  int left_ahead = 0, right_ahead = 0;
  std::vector<Pose> bodies;
  for (double t = 0.0; t < 2.0; t += 0.05) {
    const HumanPosture p = actor.posture(t);
    actor.pose_bones(t, bodies);
    const Pose root = actor.root_pose(t);
    const double lead = (root.inverse() * bodies[body_of(rig, "foot_l")].translation()).x() -
                        (root.inverse() * bodies[body_of(rig, "foot_r")].translation()).x();
    // Near the ends of a stride (hips 35+ deg apart, knees nearly straight)
    // the forward leg's foot is clearly ahead; mid-swing a bent knee can
    // hold it back, as on the primitive person.
    if (p.hip[0] - p.hip[1] > deg(35.0)) {
      EXPECT_GT(lead, 0.1) << "t " << t;
      ++left_ahead;
    }
    if (p.hip[1] - p.hip[0] > deg(35.0)) {
      EXPECT_LT(lead, -0.1) << "t " << t;
      ++right_ahead;
    }
    // Some foot is on the ground (stance leg), none below it.
    const double low = std::min(bodies[body_of(rig, "foot_l")].translation().z(),
                                bodies[body_of(rig, "foot_r")].translation().z());
    EXPECT_NEAR(
        low,
        rest_joint_position(rig.model().skeleton, find_bone(rig.model().skeleton, "foot_l")).z(),
        0.03)
        << "t " << t;
  }
  EXPECT_GT(left_ahead, 5);
  EXPECT_GT(right_ahead, 5);
}

}  // namespace
}  // namespace depot::sim
