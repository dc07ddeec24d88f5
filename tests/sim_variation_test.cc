// Seeds vary the world: actor timing, lanes and variants come from the seed
// (or from `seed_world`, which fixes them), deterministically, and a varied
// path stays within its lane and never closer to static geometry than the
// written one (ground truth only: no images, fast).
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/testing/error_of.h"
#include "dataset/object_poses.h"
#include "dataset/objects.h"
#include "sim/actors/actor_variation.h"
#include "sim/pipeline/export_truth.h"
#include "sim/scenario/scenario_loader.h"
#include "sim/scene/obstacles.h"
#include "tests/support/dataset_reader.h"
#include "tests/support/render_helpers.h"

namespace depot::test {
namespace {

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

struct Truth {
  std::string object_poses, groundtruth, objects, info;
  std::map<std::string, Eigen::Vector3d> first_positions;  // actor name -> frame 0
};

// `depot sim truth` in-process: 60 frames of a shipped scenario.
Truth truth(const std::string& scenario, uint64_t seed,
            const std::vector<YamlOverride>& overrides = {}, double load = 1.0) {
  sim::RenderRequest request;
  request.dataset.output = temp_path("truth");
  request.frames = 60;
  request.seed = seed;
  request.dynamic_load = load;
  request.progress = false;
  sim::export_truth(sim::load_scenario(scenario_path(scenario), overrides), request);
  Truth t;
  t.object_poses = read_file(request.dataset.output + "/object_poses.txt");
  t.groundtruth = read_file(request.dataset.output + "/groundtruth.txt");
  t.objects = read_file(request.dataset.output + "/objects.json");
  t.info = read_file(request.dataset.output + "/info.json");
  // Names from objects.json, positions from the first frame's records of
  // object_poses.txt.
  std::map<int, std::string> names;
  for (const dataset::ObjectRecord& o : dataset::read_objects(request.dataset.output).objects)
    names[o.id] = o.name;
  const std::vector<dataset::ObjectPoseRecord> poses =
      dataset::read_object_poses(request.dataset.output);
  for (const dataset::ObjectPoseRecord& r : poses) {
    if (r.timestamp != poses.front().timestamp) break;
    t.first_positions[names.at(r.id)] = r.pose.translation();
  }
  return t;
}

TEST(WorldSeed, SeedsMoveTheActors) {
  const Truth one = truth("depot_walking_xyz", 1), two = truth("depot_walking_xyz", 2);
  EXPECT_NE(one.object_poses, two.object_poses);
  for (const char* walker : {"walker_1", "walker_2"}) {
    EXPECT_GT((one.first_positions.at(walker) - two.first_positions.at(walker)).norm(), 0.05)
        << walker << " starts at the same place for seeds 1 and 2";
  }
  // Variants: the people's sizes (hence their extents) differ too.
  EXPECT_NE(one.objects, two.objects);
  // The patrol's animals and bird too.
  const Truth p1 = truth("depot_patrol", 1), p2 = truth("depot_patrol", 2);
  for (const char* actor : {"worker_1", "dog_1", "cat_1", "bird_1", "pig_1"})
    EXPECT_GT((p1.first_positions.at(actor) - p2.first_positions.at(actor)).norm(), 0.05) << actor;
}

TEST(WorldSeed, SameSeedGivesByteIdenticalTruth) {
  const Truth a = truth("depot_walking_xyz", 3), b = truth("depot_walking_xyz", 3);
  EXPECT_EQ(a.object_poses, b.object_poses);
  EXPECT_EQ(a.groundtruth, b.groundtruth);
  EXPECT_EQ(a.objects, b.objects);
}

TEST(WorldSeed, SeedWorldFixesTheWorld) {
  const std::vector<YamlOverride> fixed = {{"seed_world", "5"}};
  const Truth one = truth("depot_walking_xyz", 1, fixed),
              two = truth("depot_walking_xyz", 2, fixed);
  EXPECT_EQ(one.object_poses, two.object_poses)
      << "seed_world: the world is the same for all seeds";
  EXPECT_EQ(one.objects, two.objects);
  EXPECT_NE(one.groundtruth, two.groundtruth) << "the seed still moves the hand-held camera";
  EXPECT_THAT(two.info, ::testing::HasSubstr("\"seed\": 2")) << two.info;
  EXPECT_THAT(two.info, ::testing::HasSubstr("\"world_seed\": 5")) << two.info;
  // seed_world: N is the world that seed N draws.
  EXPECT_EQ(one.object_poses, truth("depot_walking_xyz", 5).object_poses);
}

// Lanes with little room: 'between' walks out between the crate stack
// 'crates_e' (x 7.6..8.8, y -3.1..-1.7; 0.25 m) and the rack 'rack_m4'
// (y -0.9..-0.1; 0.13 m on the way back); 'beside' loops 0.27 m east of the
// crates, with the wall 0.5 m on its other side.
std::string tight_lanes() {
  return std::string("scene: ") + DEPOT_SOURCE_DIR +
         "/scenes/depot.yaml\nclasses: " + DEPOT_SOURCE_DIR +
         "/scenes/classes.yaml\n"
         "motion: {type: static, position: [0, 0.6, 1.3], look_at: [0, 4, 1]}\n"
         "actors:\n"
         "  - {name: between, type: human, loop: false, path: [[6.0, -1.43], [9.0, -1.43]]}\n"
         "  - {name: beside, type: dog, path: [[9.1, -3.6], [9.1, -1.3], [9.5, -1.3], [9.5, "
         "-3.6]]}\n";
}

// Every lane actor of `scenario` over `seeds`: the varied path stays within
// its lane and clear of geometry. Returns how many actors were shifted.
int check_lanes(const std::string& path, int seeds,
                const std::vector<YamlOverride>& overrides = {}) {
  sim::Scenario scenario = sim::load_scenario(path, overrides);
  const sim::SceneLayout layout = scenario.layout;
  int shifted = 0;
  for (uint64_t seed = 1; seed <= static_cast<uint64_t>(seeds); ++seed) {
    const sim::StaticObstacles obstacles(layout, seed);
    const std::vector<sim::ActorSpec> varied =
        sim::vary_actors(scenario.actors, seed, obstacles.column_clearance());
    for (size_t i = 0; i < varied.size(); ++i) {
      const sim::ActorSpec& a = varied[i];
      if (!sim::has_lane(a)) {
        EXPECT_EQ(a.lane.bound(), 0.0) << a.name;
        EXPECT_EQ(a.path, scenario.actors[i].path) << a.name;
        continue;
      }
      shifted += a.lane.bound() > 0.01;
      const double half_width = sim::lane_half_width(a);
      double widest = 0.0, written_clearance = 1e9, varied_clearance = 1e9;
      for (const sim::LaneSample& s :
           sim::lane_samples(scenario.actors[i], a, obstacles.column_clearance())) {
        written_clearance = std::min(written_clearance, s.written_clearance);
        varied_clearance = std::min(varied_clearance, s.varied_clearance);
        const double shift = (s.varied - s.written).norm();
        widest = std::max(widest, shift);
        EXPECT_LE(shift, half_width + 1e-9) << path << " " << a.name << " seed " << seed;
        EXPECT_GE(s.varied_clearance, std::min(s.written_clearance, sim::kActorClearance) - 1e-9)
            << path << " " << a.name << " seed " << seed << " at (" << s.varied.transpose()
            << "): " << s.varied_clearance << " m from geometry, written " << s.written_clearance
            << " m";
      }
      EXPECT_NEAR(widest, a.lane.bound(), 0.02) << a.name << ": the samples see the shift";
      std::printf("%s seed %d %-10s lane shift up to %.2f m; clearance %.2f m (written %.2f m)\n",
                  scenario.name.c_str(), static_cast<int>(seed), a.name.c_str(), a.lane.bound(),
                  varied_clearance, written_clearance);
    }
  }
  return shifted;
}

TEST(WorldSeed, VariedPathsStayInTheirLanesAndClearOfGeometry) {
  int shifted = 0, lanes = 0;
  for (const std::string& name :
       sim::list_scenarios(std::string(DEPOT_SOURCE_DIR) + "/scenarios")) {
    shifted += check_lanes(scenario_path(name), 6);
    for (const auto& a : sim::load_scenario(scenario_path(name)).actors)
      lanes += 6 * sim::has_lane(a);
  }
  EXPECT_GT(shifted, lanes / 2) << "most lanes are actually shifted";
  // Clones of the dynamic load have lanes of their own.
  EXPECT_GT(check_lanes(scenario_path("depot_patrol"), 2, {{"dynamic_load", "3"}}), 10);
  const std::string tight = temp_path("tight") + ".yaml";
  std::ofstream(tight) << tight_lanes();
  EXPECT_GT(check_lanes(tight, 12), 0);
}

TEST(WorldSeed, PushersKeepTheirPathAndSittersTheirChair) {
  // Pushers, sitters, chairs and carts of the shipped scenarios, over seeds:
  // only a pusher's start time and speed (and everyone's appearance) change.
  int pushers = 0, others = 0;
  for (const char* name : {"depot_walking_xyz", "depot_sitting_static", "depot_patrol"}) {
    const sim::Scenario s = sim::load_scenario(scenario_path(name));
    for (uint64_t seed = 1; seed <= 4; ++seed) {
      const sim::StaticObstacles obstacles(s.layout, seed);
      const auto varied = sim::vary_actors(s.actors, seed, obstacles.column_clearance());
      for (size_t i = 0; i < varied.size(); ++i) {
        const sim::ActorSpec &a = s.actors[i], &v = varied[i];
        if (sim::has_lane(a)) continue;
        EXPECT_EQ(v.path, a.path) << v.name;
        EXPECT_EQ(v.position, a.position) << v.name;
        EXPECT_EQ(v.start_offset, a.start_offset) << v.name;
        EXPECT_EQ(v.lane.bound(), 0.0) << v.name;
        EXPECT_EQ(v.target, a.target) << v.name;
        if (v.action == "push") {
          ++pushers;
          EXPECT_GE(v.start_time, a.start_time) << v.name;
          EXPECT_LE(v.start_time, a.start_time + 1.0) << v.name;
          EXPECT_NEAR(v.speed, a.speed, 0.08 * a.speed) << v.name;
        } else {
          ++others;
          EXPECT_EQ(v.start_time, a.start_time) << v.name;
          EXPECT_EQ(v.speed, a.speed) << v.name;
        }
      }
    }
  }
  EXPECT_EQ(pushers, 2 * 4);
  EXPECT_EQ(others, (3 + 4 + 1) * 4);  // chairs and sitters, chairs and sitters, the cart
}

// A person's size varies with the seed (0.92..1.07): a pusher must start
// with its hands clear of its chair at the largest size, or the chair is
// flung away while physics settles, before the first frame.
std::string pusher_starting_at(double x) {
  return std::string("scene: ") + DEPOT_SOURCE_DIR +
         "/scenes/depot.yaml\nclasses: " + DEPOT_SOURCE_DIR +
         "/scenes/classes.yaml\nframes: 10\n"
         "motion: {type: static, position: [0, 0.6, 1.3], look_at: [0, 4, 1]}\n"
         "actors:\n"
         "  - {name: chair_pushed, type: chair, position: [-1.6, 2.35], yaw_deg: 0}\n"
         "  - {name: pusher_1, type: human, pushes: chair_pushed, loop: false, start_time: 1.0, "
         "path: [[" +
         std::to_string(x) + ", 2.35], [0.4, 2.35]]}\n";
}

TEST(WorldSeed, PushersStartClearOfTheirTarget) {
  const std::string close = temp_path("pusher_close") + ".yaml";
  std::ofstream(close) << pusher_starting_at(-2.45);
  sim::RenderRequest request;
  request.dataset.output = temp_path("out");
  request.progress = false;
  const std::string message =
      error_of([&] { sim::export_truth(sim::load_scenario(close), request); });
  EXPECT_EQ(
      message.rfind(close + ": actor 'pusher_1' starts with its hands inside 'chair_pushed'", 0),
      0u)
      << message;
  EXPECT_THAT(message, ::testing::HasSubstr("at least 0.20 m further")) << message;
  const std::string clear = temp_path("pusher_clear") + ".yaml";
  std::ofstream(clear) << pusher_starting_at(-2.65);
  EXPECT_EQ(error_of([&] { sim::export_truth(sim::load_scenario(clear), request); }), "");
  // The shipped pushed chair and cart stand where they were put at frame 0,
  // whatever the seed (sizes and start times vary) and the dynamic load.
  for (uint64_t seed = 1; seed <= 6; ++seed) {
    const double load = seed <= 4 ? 1.0 : 4.0;
    const Truth t = truth("depot_walking_xyz", seed, {}, load);
    EXPECT_LT((t.first_positions.at("chair_pushed") - Eigen::Vector3d(-1.6, 2.35, 0)).norm(), 1e-3)
        << "seed " << seed << " load " << load;
    const Truth p = truth("depot_patrol", seed, {}, load);
    EXPECT_LT((p.first_positions.at("cart_1") - Eigen::Vector3d(-2.6, -3.3, 0)).norm(), 1e-3)
        << "seed " << seed << " load " << load;
  }
}

}  // namespace
}  // namespace depot::test
