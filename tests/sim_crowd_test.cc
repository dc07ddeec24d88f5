// Crowds (#27): the busy aisle of depot_crowd at dynamic load 2 (32 walkers),
// checked over its whole sequence as the world poses them: no two walkers
// ever closer than the crowd's spacing, none inside the racks or the goods,
// every one walking (some wait in the throng); and the moving share the load was raised for.
#include <gtest/gtest.h>

#include <map>

#include "eval/motion_truth.h"
#include "sim/actors/crowd.h"
#include "sim/scenario/scenario_loader.h"
#include "sim/scene/obstacles.h"
#include "sim/world/simulated_sequence.h"
#include "tests/support/render_helpers.h"

namespace depot::test {
namespace {

TEST(Crowd, NoWalkerEverStandsInAnotherOrInTheStaticScene) {
  sim::Scenario s = sim::load_scenario(scenario_path("depot_crowd"));
  sim::apply_dynamic_load(s, 2.0);
  sim::SimulatedSequence sequence(s, sim::GlBackend::kOsMesa, /*render=*/false);
  const sim::StaticObstacles obstacles(s.layout, s.world_seed());
  std::vector<const sim::Instance*> walkers;
  for (const sim::Instance& inst : sequence.world().instances())
    if (inst.name.rfind("aisle_", 0) == 0) walkers.push_back(&inst);
  ASSERT_EQ(walkers.size(), 32u);

  std::map<const sim::Instance*, Eigen::Vector2d> start, last;
  std::map<const sim::Instance*, double> walked;
  double closest = 1e9, nearest_geometry = 1e9;
  int frames = 0;
  sim::FrameTruth truth;
  while (sequence.next_truth(truth)) {
    ++frames;
    std::vector<Eigen::Vector2d> at;
    for (const sim::Instance* w : walkers) {
      const Eigen::Vector2d p = sequence.world().instance_pose(*w).translation().head<2>();
      if (!start.count(w)) start[w] = last[w] = p;
      walked[w] += (p - last[w]).norm();
      last[w] = p;
      at.push_back(p);
      nearest_geometry = std::min(nearest_geometry, obstacles.nearest_column(p, 0.0, 1.9).distance);
    }
    for (size_t i = 0; i < at.size(); ++i)
      for (size_t j = i + 1; j < at.size(); ++j)
        closest = std::min(closest, (at[i] - at[j]).norm());
  }
  EXPECT_EQ(frames, s.frames);
  std::printf("%d frames, 32 walkers: closest pair %.3f m, nearest static geometry %.3f m\n",
              frames, closest, nearest_geometry);
  EXPECT_GE(closest, sim::kCrowdSpacing - 1e-3);
  EXPECT_GE(nearest_geometry, sim::kCrowdClearance - 0.02);
  for (const auto& [w, d] : walked) EXPECT_GT(d, 2.0) << w->name << " hardly walked";
}

TEST(Crowd, DynamicLoadTwoFillsMostOfTheViewWithMovers) {
  const std::string data = render_small({"depot_crowd", 60, 160, false, {}, false});
  SmallRender doubled("depot_crowd", 60, 160, false);
  doubled.set = {{"dynamic_load", "2"}};
  const std::string crowded = render_small(doubled);
  auto mean_share = [](const std::string& dataset) {
    const eval::MotionTruth truth(dataset);
    double sum = 0;
    for (double t : truth.timestamps()) sum += truth.moving_fraction(t);
    return sum / truth.timestamps().size();
  };
  const double one = mean_share(data), two = mean_share(crowded);
  std::printf("moving share: load 1 %.3f, load 2 %.3f\n", one, two);
  EXPECT_GT(two, 0.55);
  EXPECT_GT(two, one + 0.05);
}

}  // namespace
}  // namespace depot::test
