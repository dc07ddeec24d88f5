// Distances to the static scene: exact for boxes and upright cylinders, walls
// and ceiling count, the floor does not.
#include "sim/scene/obstacles.h"

#include <gtest/gtest.h>

namespace depot::sim {
namespace {

SceneLayout hall_with(std::vector<SceneObject> objects) {
  SceneLayout l;
  l.length = 20;
  l.width = 12;
  l.height = 4.5;
  l.objects = std::move(objects);
  return l;
}

SceneObject object(const std::string& type, const std::string& name, Eigen::Vector2d at,
                   double yaw_deg = 0) {
  SceneObject o;
  o.type = type;
  o.name = name;
  o.position = at;
  o.yaw_deg = yaw_deg;
  return o;
}

TEST(StaticObstacles, BarrelIsAnUprightCylinder) {
  // A barrel: radius 0.29 m, 0.88 m tall, standing at (2, 1).
  const StaticObstacles o(hall_with({object("barrel", "b", {2.0, 1.0})}), 1);
  ASSERT_EQ(o.size(), 1u);
  EXPECT_NEAR(o.nearest({3.0, 1.0, 0.5}).distance, 0.71, 1e-9);
  EXPECT_EQ(o.nearest({3.0, 1.0, 0.5}).object, "'b' (barrel)");
  // Diagonal: the round side, not a box corner.
  EXPECT_NEAR(o.nearest({2.0 + 0.5, 1.0 + 0.5, 0.5}).distance, std::sqrt(0.5) - 0.29, 1e-9);
  EXPECT_NEAR(o.nearest({2.0, 1.0, 1.18}).distance, 0.30, 1e-9);   // above the lid
  EXPECT_NEAR(o.nearest({2.0, 1.0, 0.44}).distance, -0.29, 1e-9);  // inside: negative
  // A body standing 0.5 m from the centre, 0..1.8 m tall: 0.21 m; a bird
  // flying over it at 1.2..1.4 m: the height gap counts.
  EXPECT_NEAR(o.nearest_column({2.5, 1.0}, 0.0, 1.8).distance, 0.21, 1e-9);
  EXPECT_NEAR(o.nearest_column({2.5, 1.0}, 1.2, 1.4).distance, std::hypot(0.21, 0.32), 1e-9);
}

TEST(StaticObstacles, DoorIsARotatedBox) {
  // A door: 0.06 x 2.4 x 3 m slab; turned 90 degrees it spans x, not y.
  const StaticObstacles straight(hall_with({object("door", "d", {0.0, 0.0})}), 1);
  const StaticObstacles turned(hall_with({object("door", "d", {0.0, 0.0}, 90)}), 1);
  EXPECT_NEAR(straight.nearest({1.0, 0.0, 1.5}).distance, 0.97, 1e-9);
  EXPECT_NEAR(straight.nearest({0.0, 2.0, 1.5}).distance, 0.8, 1e-9);
  EXPECT_NEAR(turned.nearest({0.0, 2.0, 1.5}).distance, 1.97, 1e-9);
  EXPECT_NEAR(turned.nearest({1.0, 0.0, 1.5}).distance, -0.03, 1e-9);  // in the slab
  EXPECT_NEAR(turned.nearest_column({2.0, 0.0}, 0.0, 1.0).distance, 0.8, 1e-9);
}

TEST(StaticObstacles, WallsAndCeilingButNotTheFloor) {
  const StaticObstacles empty(hall_with({}), 1);
  EXPECT_EQ(empty.size(), 0u);
  const Nearest east = empty.nearest({9.7, 0.0, 2.0});
  EXPECT_NEAR(east.distance, 0.3, 1e-9);
  EXPECT_EQ(east.object, "the east wall");
  EXPECT_EQ(empty.nearest({0.0, -5.9, 2.0}).object, "the south wall");
  EXPECT_EQ(empty.nearest({0.0, 0.0, 4.3}).object, "the ceiling");
  EXPECT_NEAR(empty.nearest({0.0, 0.0, 0.05}).distance, 4.45, 1e-9) << "the floor is no obstacle";
}

TEST(StaticObstacles, GoodsOnRacksAreObstacles) {
  // A rack's frame and the goods on its shelves, as the renderer builds them.
  const StaticObstacles o(hall_with({object("rack", "r", {0.0, 0.0})}), 3);
  EXPECT_GT(o.size(), 20u);
  EXPECT_LT(o.nearest({1.16, 0.36, 0.5}).distance, 0.0) << "inside a post";
  EXPECT_NEAR(o.nearest({0.0, -1.4, 0.12}).distance, 1.0, 1e-9) << "front beam at y = -0.4";
}

}  // namespace
}  // namespace depot::sim
