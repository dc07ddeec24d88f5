// The procedural hall: drawn from the world seed and the same for the same
// seed, rows and aisles where the parameters put them, routes along the
// aisles, bad parameters one error naming the key, and a scenario's motion and
// actors following the routes of the hall its seed draws.
#include "sim/scenario/procedural_hall.h"

#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/testing/error_of.h"
#include "common/testing/scratch_folder.h"
#include "sim/scenario/scenario_loader.h"

namespace depot::sim {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

ProceduralHallSpec ranges() {
  ProceduralHallSpec s;
  s.length = {18, 26, "f:1"};
  s.width = {17, 21, "f:2"};
  s.rack_rows = {1, 2, "f:3"};
  s.aisle_width = {2.6, 3.2, "f:4"};
  s.cross_aisle = {3.0, 4.0, "f:5"};
  s.clutter = {0.4, 0.9, "f:6"};
  return s;
}

int count_type(const SceneLayout& l, const std::string& type) {
  int n = 0;
  for (const auto& o : l.objects) n += o.type == type;
  return n;
}

TEST(ProceduralHall, TheSameSeedGivesTheSameHallAndOthersDiffer) {
  const ProceduralHallSpec spec = ranges();
  check_procedural_hall(spec);
  std::set<std::string> halls;
  for (uint64_t seed = 1; seed <= 5; ++seed) {
    const std::string a = scene_layout_yaml(generate_procedural_hall(spec, seed));
    EXPECT_EQ(a, scene_layout_yaml(generate_procedural_hall(spec, seed))) << "seed " << seed;
    halls.insert(a);
  }
  EXPECT_EQ(halls.size(), 5u);
}

TEST(ProceduralHall, RowsAislesAndRoutesFollowTheParameters) {
  ProceduralHallSpec spec;
  spec.length = {20, 20, ""};
  spec.width = {17, 17, ""};
  spec.rack_rows = {2, 2, ""};
  spec.aisle_width = {3, 3, ""};
  spec.rack_length = {2.5, 2.5, ""};
  spec.cross_aisle = {4, 4, ""};
  check_procedural_hall(spec);
  const SceneLayout l = generate_procedural_hall(spec, 3);
  EXPECT_DOUBLE_EQ(l.length, 20);
  EXPECT_DOUBLE_EQ(l.width, 17);
  for (const char* route :
       {"aisle_1", "aisle_2", "aisle_3", "cross", "loop_row_1", "loop_row_2", "patrol"})
    EXPECT_EQ(l.routes.count(route), 1u) << route;
  EXPECT_EQ(l.routes.count("aisle_4"), 0u);
  // Aisle centres: 3 m apart from the racks either side (north row face at
  // 8.5 - 0.05 - 0.8 = 7.65; row 1 from 4.65 to 2.95; row 2 from -0.05 to -1.75).
  EXPECT_NEAR(l.routes.at("aisle_1")[0].y(), 7.65 - 1.5, 1e-9);
  EXPECT_NEAR(l.routes.at("aisle_2")[0].y(), 2.95 - 1.5, 1e-9);
  EXPECT_NEAR(l.routes.at("aisle_3")[0].y(), -1.75 - 1.5, 1e-9);
  // Racks: none inside an aisle, none in the cross aisle, rows end an aisle
  // from the end walls.
  const double xc = l.routes.at("cross")[0].x();
  int middle = 0;
  for (const auto& o : l.objects) {
    if (o.type != "rack") continue;
    for (const auto& [name, points] : l.routes) {
      if (name.rfind("aisle_", 0) == 0) {
        EXPECT_GE(std::abs(o.position.y() - points[0].y()), 1.5 + 0.4 - 1e-9) << o.name << name;
      }
    }
    if (o.name.rfind("rack_r", 0) != 0) continue;
    ++middle;
    EXPECT_GE(std::abs(o.position.x() - xc), 2.0 + 1.25 - 1e-9) << o.name;
    EXPECT_LE(std::abs(o.position.x()) + 1.25, 10 - 3 + 1e-9) << o.name;
  }
  EXPECT_GE(middle, 8);
  EXPECT_EQ(count_type(l, "workbench"), 1);
  EXPECT_EQ(count_type(l, "desk"), 1);
  EXPECT_EQ(count_type(l, "door"), 1);
  EXPECT_EQ(l.lights.size(), 6u);  // 2 rows of round(20 / 6) = 3
  for (const auto& light : l.lights) EXPECT_NEAR(light.position.z(), 4.3, 1e-9);
}

TEST(ProceduralHall, ClutterFillsTheWorkArea) {
  ProceduralHallSpec spec;
  spec.clutter = {0, 0, ""};
  const SceneLayout empty = generate_procedural_hall(spec, 4);
  spec.clutter = {1, 1, ""};
  const SceneLayout full = generate_procedural_hall(spec, 4);
  auto goods = [](const SceneLayout& l) {
    int n = 0;
    for (const auto& o : l.objects) n += o.name.rfind("goods_", 0) == 0;
    return n;
  };
  EXPECT_EQ(goods(empty), 0);
  EXPECT_GE(goods(full), 5);  // every place of 2.2 m along the 20 m wall but two
}

TEST(ProceduralHall, ALayoutWrittenOutReadsBackTheSame) {
  const SceneLayout l = generate_procedural_hall(ranges(), 2);
  const std::string text = scene_layout_yaml(l);
  const testkit::ScratchFolder scratch("procedural");
  const std::string path = scratch.write("scene.yaml", text);
  const SceneLayout back = load_scene_layout(path);
  EXPECT_EQ(back.objects.size(), l.objects.size());
  EXPECT_EQ(back.lights.size(), l.lights.size());
  EXPECT_EQ(back.routes.size(), l.routes.size());
  SceneLayout named = back;
  named.path = l.path;
  EXPECT_EQ(scene_layout_yaml(named), text);
}

TEST(ProceduralHall, BadParametersAreOneErrorNamingTheKey) {
  auto error = [](auto change) {
    ProceduralHallSpec s = ranges();
    change(s);
    return error_of([&] { check_procedural_hall(s); });
  };
  EXPECT_EQ(error([](ProceduralHallSpec& s) {
              s.aisle_width = {1.2, 2.0, "f:4"};
            }),
            "f:4: hall.aisle_width 1.20 m is narrower than the robot and its clearance "
            "(robot_width 0.80 m + 2 x 0.40 m = 1.60 m)");
  EXPECT_THAT(error([](ProceduralHallSpec& s) { s.robot_width = 2.5; }),
              StartsWith("f:4: hall.aisle_width 2.60 m is narrower than the robot"));
  EXPECT_EQ(error([](ProceduralHallSpec& s) {
              s.width = {12, 21, "f:2"};
            }),
            "f:2: hall.width 12.00 m is too narrow for 2 rack rows with 3.20 m aisles and the "
            "3.0 m work area (needs 16.85 m)");
  EXPECT_THAT(error([](ProceduralHallSpec& s) {
                s.length = {9, 26, "f:1"};
              }),
              StartsWith("f:1: hall.length 9.00 m is too short for a rack row"));
  EXPECT_EQ(error([](ProceduralHallSpec& s) {
              s.clutter = {0.9, 0.4, "f:6"};
            }),
            "f:6: hall.clutter must be a number or a range [low, high] with low <= high");
  EXPECT_EQ(error([](ProceduralHallSpec& s) {
              s.rack_rows = {1.5, 2, "f:3"};
            }),
            "f:3: hall.rack_rows must be whole numbers");
  EXPECT_EQ(error([](ProceduralHallSpec& s) {
              s.cross_aisle = {1, 1, "f:5"};
            }),
            "f:5: hall.cross_aisle 1.00 m is narrower than the robot and its clearance (1.60 "
            "m); 0 = no cross aisle");
  EXPECT_THAT(error([](ProceduralHallSpec& s) {
                s.clutter = {0, 2, "f:6"};
              }),
              HasSubstr("hall.clutter = [0, 2] is out of range [0, 1]"));
}

const char* kScenario = R"(name: hall
scene: procedural
seed: 1
hall: {length: [18, 26], width: [17, 21], rack_rows: [1, 2], cross_aisle: [3, 4]}
motion: {type: waypoints, route: patrol, height: 0.9}
actors:
  - {name: w, type: human, route: aisle_1, loop: false}
)";

TEST(ProceduralHallScenario, MotionAndActorsFollowTheRoutesOfTheSeedsHall) {
  const testkit::ScratchFolder scratch("procedural");
  const std::string path = scratch.write("hall.yaml", kScenario);
  Scenario s = load_scenario(path);
  ASSERT_TRUE(s.procedural);
  EXPECT_EQ(s.motion.path, s.layout.routes.at("patrol"));
  EXPECT_EQ(s.actors.at(0).path, s.layout.routes.at("aisle_1"));
  const std::string hall1 = scene_layout_yaml(s.layout);
  // Another seed draws another hall, and the routes follow it.
  set_scenario_seed(s, 2);
  EXPECT_NE(scene_layout_yaml(s.layout), hall1);
  EXPECT_EQ(s.motion.path, s.layout.routes.at("patrol"));
  EXPECT_EQ(s.actors.at(0).path, s.layout.routes.at("aisle_1"));
  // seed_world holds the hall whatever the seed.
  Scenario fixed = load_scenario(path, {{"seed_world", "1"}});
  set_scenario_seed(fixed, 2);
  EXPECT_EQ(scene_layout_yaml(fixed.layout), hall1);
}

TEST(ProceduralHallScenario, MistakesAreOneErrorLine) {
  const testkit::ScratchFolder scratch("procedural");
  const std::string path = scratch.write("bad_hall.yaml", kScenario);
  EXPECT_THAT(error_of([&] {
                load_scenario(path, {{"hall.aisle_width", "1"}});
              }),
              StartsWith(path + ": --set hall.aisle_width=1: hall.aisle_width 1.00 m is "
                                "narrower than the robot"));
  EXPECT_THAT(error_of([&] {
                load_scenario(path, {{"hall.aisles", "3"}});
              }),
              HasSubstr("unknown key 'aisles'"));
  EXPECT_THAT(error_of([&] {
                load_scenario(path, {{"actors", "[{type: dog, route: aisle_9}]"}});
              }),
              HasSubstr("actor 'dog_0' follows route 'aisle_9', which procedural hall (world "
                        "seed 1) does not have (its routes: aisle_1, "));
  EXPECT_THAT(error_of([&] {
                load_scenario(path, {{"scene", "depot.yaml"}});
              }),
              HasSubstr("'hall' sets a generated hall's parameters: it needs 'scene: "
                        "procedural'"));
  EXPECT_THAT(error_of([&] {
                load_scenario(
                    path, {{"motion", "{type: waypoints, route: patrol, path: [[0, 0], [1, 1]]}"}});
              }),
              HasSubstr("motion takes a 'path' or a 'route', not both"));
}

}  // namespace
}  // namespace depot::sim
