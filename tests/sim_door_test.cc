// A door in a rendered world (#27): its leaf is a labelled instance of class
// door whose truth is moving exactly while it swings, and whose pose turns
// about the hinge as its events say.
#include <gtest/gtest.h>

#include "sim/scenario/scenario_loader.h"
#include "sim/world/simulated_sequence.h"
#include "tests/support/render_helpers.h"

namespace depot::test {
namespace {

TEST(SimDoor, TheLeafMovesExactlyWhileItSwings) {
  sim::Scenario s = sim::load_scenario(
      scenario_path("depot_static"),
      {{"frames", "90"},
       {"doors",
        "[{name: d, hinge: [-0.5, -5.97], width: 1.0, swing_deg: 90, events: [[1, 0], [2, 1]]}]"}});
  sim::SimulatedSequence sequence(s, sim::GlBackend::kOsMesa, /*render=*/false);
  const sim::Instance* door = nullptr;
  for (const sim::Instance& inst : sequence.world().instances())
    if (inst.name == "d") door = &inst;
  ASSERT_NE(door, nullptr);
  EXPECT_EQ(door->class_name, "door");
  int moving_before = 0, moving_during = 0, moving_after = 0, during = 0;
  sim::FrameTruth truth;
  while (sequence.next_truth(truth)) {
    const double t = truth.rgb_timestamp - s.timestamps.start;
    for (const auto& o : truth.objects) {
      if (o.id != door->id) continue;
      if (t < 0.95) moving_before += o.moving;
      if (t > 1.05 && t < 1.95) moving_during += o.moving, ++during;
      if (t > 2.05) moving_after += o.moving;
    }
  }
  EXPECT_EQ(moving_before, 0);
  EXPECT_EQ(moving_during, during);
  EXPECT_GT(during, 20);
  EXPECT_EQ(moving_after, 0);
  // Open: the leaf turned 90 degrees about the hinge.
  const Pose hinge = sequence.world().instance_pose(*door);
  EXPECT_NEAR(hinge.linear()(1, 0), 1.0, 1e-6);  // its x axis along +y
  EXPECT_TRUE(hinge.translation().isApprox(Eigen::Vector3d(-0.5, -5.97, 0.0), 1e-9));
}

}  // namespace
}  // namespace depot::test
