// Generated halls built as the renderer builds them: every route keeps the
// robot's clearance from every static surface at every height it spans, and
// no two objects stand in each other.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sim/scenario/procedural_hall.h"
#include "sim/scenario/scenario_loader.h"
#include "sim/scenario/shipped_scenarios.h"
#include "sim/scene/depot_objects.h"
#include "sim/scene/obstacles.h"

namespace depot::sim {
namespace {

// The hall of the shipped scenarios/depot_procedural_patrol.yaml.
ProceduralHallSpec shipped_ranges() {
  const Scenario s = load_scenario(resolve_scenario("depot_procedural_patrol"));
  EXPECT_TRUE(s.procedural);
  return *s.procedural;
}

TEST(ProceduralHallGeometry, EveryRouteKeepsTheRobotClearOfTheStaticScene) {
  const ProceduralHallSpec spec = shipped_ranges();
  check_procedural_hall(spec);
  // Half the robot (0.4 m) plus its 0.4 m clearance, from the floor to 2 m.
  const double need = spec.robot_width / 2 + 0.4;
  for (uint64_t seed = 1; seed <= 8; ++seed) {
    const SceneLayout hall = generate_procedural_hall(spec, seed);
    const StaticObstacles obstacles(hall, seed);
    for (const auto& [name, points] : hall.routes) {
      const bool closed = name == "patrol" || name.rfind("loop_row_", 0) == 0;
      for (size_t i = 0; i + (closed ? 0 : 1) < points.size(); ++i) {
        const Eigen::Vector2d a = points[i], b = points[(i + 1) % points.size()];
        for (double t = 0; t <= 1.0; t += 0.02) {
          const Eigen::Vector2d p = a + t * (b - a);
          const Nearest n = obstacles.nearest_column(p, 0.05, 2.0);
          ASSERT_GE(n.distance, need)
              << "seed " << seed << " route " << name << " at (" << p.x() << ", " << p.y()
              << ") is " << n.distance << " m from " << n.object;
        }
      }
    }
  }
}

TEST(ProceduralHallGeometry, NoTwoObjectsStandInEachOther) {
  const ProceduralHallSpec spec = shipped_ranges();
  for (uint64_t seed = 1; seed <= 8; ++seed) {
    const SceneLayout hall = generate_procedural_hall(spec, seed);
    struct Placed {
      std::string object;
      Eigen::AlignedBox3d box;
    };
    std::vector<Placed> placed;
    for (const SceneObject& o : hall.objects) {
      Eigen::AlignedBox3d box;
      for (const InstanceGeometry& g : build_scene_object(o, seed)) {
        const Eigen::AlignedBox3d local = local_bounds(g.geoms);
        for (int c = 0; c < 8; ++c)
          box.extend(g.pose * local.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c)));
      }
      ASSERT_LE(std::abs(box.min().x()), hall.length / 2 + 1e-6) << o.name;
      ASSERT_LE(std::abs(box.max().x()), hall.length / 2 + 1e-6) << o.name;
      ASSERT_LE(std::abs(box.min().y()), hall.width / 2 + 1e-6) << o.name;
      ASSERT_LE(std::abs(box.max().y()), hall.width / 2 + 1e-6) << o.name;
      for (const Placed& p : placed) {
        const Eigen::AlignedBox3d common = p.box.intersection(box);
        const bool overlap = !common.isEmpty() && common.sizes().minCoeff() > 0.005;
        EXPECT_FALSE(overlap) << "seed " << seed << ": " << o.name << " stands in " << p.object;
      }
      placed.push_back({o.name, box});
    }
  }
}

}  // namespace
}  // namespace depot::sim
