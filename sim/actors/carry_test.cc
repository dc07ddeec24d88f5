// A carrier and its goods over time: the goods rest still before the first
// lift, rise into the hands, travel with the carrier to the path's end, are
// set down there on their support and rest still, then come back.
#include "sim/actors/carry.h"

#include <gtest/gtest.h>

#include "sim/actors/human.h"

namespace depot::sim {
namespace {

ActorSpec carrier(const std::string& goods = "crate") {
  ActorSpec a;
  a.name = "carrier";
  a.type = "human";
  a.action = "carry";
  a.carries = goods;
  a.path = {{0, 0}, {4, 0}};
  a.loop = false;
  a.speed = 1.0;
  a.start_time = 1.0;
  a.put_height = 0.3;
  a.appearance = 7;
  return a;
}

TEST(CarryMotion, GoodsRestLiftTravelAndAreSetDownAtTheEnd) {
  const ActorSpec spec = carrier();
  HumanActor person(spec, nullptr);
  std::unique_ptr<Actor> goods = person.make_carried_goods();
  ASSERT_TRUE(goods);
  EXPECT_EQ(goods->name(), "carrier_crate");
  EXPECT_EQ(goods->class_name(), "crate");
  const double half_height = 0.17;

  // Resting before the start, on the floor ahead of the carrier.
  const Pose rest0 = goods->root_pose(0.0);
  EXPECT_TRUE(rest0.isApprox(goods->root_pose(0.9)));
  EXPECT_NEAR(rest0.translation().z(), half_height, 1e-9);
  EXPECT_GT(rest0.translation().x(), person.root_pose(0.0).translation().x() + 0.4);

  // Lifted (kLift s), then held at the waist while the carrier walks.
  const double walking = 1.0 + kLift + 1.0;
  const Pose held = goods->root_pose(walking);
  EXPECT_GT(held.translation().z(), 0.8);
  const Pose root = person.root_pose(walking);
  EXPECT_NEAR((root.inverse() * held).translation().y(), 0.0, 1e-9);
  EXPECT_GT((root.inverse() * held).translation().x(), 0.3);
  // It travels with the carrier: 0.5 s later both moved by the same step.
  const Eigen::Vector3d step_goods =
      goods->root_pose(walking + 0.5).translation() - held.translation();
  const Eigen::Vector3d step_person =
      person.root_pose(walking + 0.5).translation() - root.translation();
  EXPECT_NEAR((step_goods - step_person).norm(), 0.0, 1e-6);
  EXPECT_GT(step_person.norm(), 0.4);

  // Set down at the end on its 0.3 m support, and still while the carrier waits.
  const Path2D path = actor_path(spec);
  const double arrive = 1.0 + kLift + 0.5 * path.length() / spec.speed;
  const Pose put = goods->root_pose(arrive + kLift + 0.05);
  EXPECT_NEAR(put.translation().z(), 0.3 + half_height, 1e-9);
  EXPECT_TRUE(put.isApprox(goods->root_pose(arrive + kLift + 0.4)));
  // At the other end of the 4 m path (its smoothed turn, goods ahead of the carrier).
  EXPECT_GT((put.translation() - rest0.translation()).head<2>().norm(), 2.0);
}

TEST(CarryMotion, ASackIsAnEllipsoidOfItsOwnClass) {
  HumanActor person(carrier("sack"), nullptr);
  const std::unique_ptr<Actor> goods = person.make_carried_goods();
  ASSERT_TRUE(goods);
  EXPECT_EQ(goods->class_name(), "sack");
  ASSERT_EQ(goods->parts().size(), 1u);
  EXPECT_EQ(goods->parts()[0].shape, Shape::kEllipsoid);
}

TEST(CarryMotion, AWalkerCarriesNothing) {
  ActorSpec walker = carrier();
  walker.action = "walk";
  walker.carries.clear();
  HumanActor person(walker, nullptr);
  EXPECT_FALSE(person.make_carried_goods());
}

}  // namespace
}  // namespace depot::sim
