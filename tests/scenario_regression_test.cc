// Scenario regression tests (label `scenario`): short versions of the
// shipped scenarios (orb, full and masked) against the reviewed bounds in
// scenarios/regression/bounds.yaml.
#include <yaml-cpp/yaml.h>

#include <gtest/gtest.h>

#include <cstdlib>

#include "common/tum_io.h"
#include "dataset/test_folder.h"
#include "eval/ate.h"
#include "eval/improvement.h"
#include "eval/matched_trajectories.h"
#include "tests/support/dataset_reader.h"
#include "tests/support/render_helpers.h"
#include "tests/support/slam_helpers.h"
#include "tools/system/system_run.h"

namespace depot::test {
namespace {

const std::string kBounds = std::string(DEPOT_SOURCE_DIR) + "/scenarios/regression/bounds.yaml";

class ScenarioRegression : public ::testing::TestWithParam<std::string> {};

TEST_P(ScenarioRegression, MeetsItsBounds) {
  const YAML::Node root = YAML::LoadFile(kBounds);
  // The longer tier (CMake -DDEPOT_LONG_TESTS=ON, label scenario_long) runs
  // the same checks over more frames.
  int frames = root["frames"].as<int>();
  YAML::Node b = root["scenarios"][GetParam()];
  ASSERT_TRUE(b) << GetParam() << " has no bounds in " << kBounds;
  if (const char* env = std::getenv("DEPOT_SCENARIO_FRAMES")) {
    frames = std::atoi(env);
    ASSERT_GE(frames, 30) << "DEPOT_SCENARIO_FRAMES must be a frame count >= 30, got " << env;
    // The long tier's own bounds (e.g. lost frames grow with length).
    for (const auto& kv : b["long"]) b[kv.first.as<std::string>()] = kv.second;
  }
  std::string data = render_small({GetParam(), frames, 640, false});
  SlamOutcome full = run_slam_mode(data, slam::RejectionMode::kFull, false);
  SlamOutcome orb = run_slam_mode(data, slam::RejectionMode::kOrb, false);
  const double rho = eval::improvement_percent(orb.ate_rmse, full.ate_rmse);
  std::printf(
      "%s (%d frames): orb ATE %.4f m (tracked %.1f %%), full ATE %.4f m (%.1f %%), precision "
      "%.3f recall %.3f, lost %d, tracked %.1f %%\n",
      GetParam().c_str(), frames, orb.ate_rmse, 100 * orb.tracked_share(), full.ate_rmse, rho,
      full.score.precision(), full.score.recall(), full.lost, 100 * full.tracked_share());
  EXPECT_LT(full.ate_rmse, b["full_ate_max"].as<double>()) << "full ATE RMSE";
  if (b["improvement_min"]) {
    EXPECT_GT(rho, b["improvement_min"].as<double>()) << "Eq. 9 improvement of full";
  }
  EXPECT_GT(full.score.recall(), b["recall_min"].as<double>()) << "rejection recall";
  EXPECT_GT(full.score.precision(), b["precision_min"].as<double>()) << "rejection precision";
  EXPECT_LE(full.lost, b["max_lost"].as<int>()) << "lost frames";
  // Honest trajectories: the poses ATE sees are the tracked frames, and
  // every frame given is accounted for.
  EXPECT_EQ(full.frames, static_cast<size_t>(frames));
  EXPECT_EQ(full.trajectory_size, full.tracked);
  EXPECT_GE(full.tracked_share(), b["tracked_share_min"].as<double>()) << "full tracked share";
  if (const YAML::Node m = b["masked"]) {
    // Our mode beyond boxes: precision with boundary points left out.
    slam::RejectionParams params;
    SlamOutcome masked = run_slam_mode(data, slam::RejectionMode::kMasked, false, params);
    std::printf(
        "%s masked: ATE %.4f m, precision %.3f (boundary static %.3f) recall %.3f, lost %d, "
        "tracked %.1f %%\n",
        GetParam().c_str(), masked.ate_rmse, masked.score.precision_without_boundary(),
        masked.score.precision(), masked.score.recall(), masked.lost, 100 * masked.tracked_share());
    EXPECT_LT(masked.ate_rmse, m["ate_max"].as<double>()) << "masked ATE RMSE";
    if (m["precision_min"]) {
      EXPECT_GT(masked.score.precision_without_boundary(), m["precision_min"].as<double>())
          << "masked precision";
    }
    if (m["recall_min"]) {
      EXPECT_GT(masked.score.recall(), m["recall_min"].as<double>()) << "masked recall";
    }
    // Seated people seen still keep their points (the still-object test):
    // recall stays low where the truth marks a whole fidgeting sitter moving.
    if (m["recall_max"]) {
      EXPECT_LT(masked.score.recall(), m["recall_max"].as<double>()) << "masked recall";
    }
    EXPECT_LE(masked.lost, m["max_lost"].as<int>()) << "masked lost frames";
    EXPECT_EQ(masked.trajectory_size, masked.tracked);
    EXPECT_GE(masked.tracked_share(), m["tracked_share_min"].as<double>())
        << "masked tracked share";
  }
}

// Other systems under test ("system:NAME" entries), through the path a
// user's system takes (tools/system/system_run.h): ATE and tracked share.
TEST_P(ScenarioRegression, SystemsUnderTestMeetTheirBounds) {
  const YAML::Node root = YAML::LoadFile(kBounds);
  const YAML::Node b = root["scenarios"][GetParam()];
  std::vector<std::string> systems;
  for (const auto& kv : b)
    if (system::is_system_mode(kv.first.as<std::string>()))
      systems.push_back(kv.first.as<std::string>());
  if (systems.empty()) GTEST_SKIP() << GetParam() << " has no system:NAME bounds";
  const std::string data = render_small({GetParam(), root["frames"].as<int>(), 640, false});
  for (const std::string& mode : systems) {
    const YAML::Node bounds = b[mode];
    system::SystemRunRequest request;
    request.dataset = data;
    request.work_dir = temp_path("system");
    request.log_path = request.work_dir + ".log";
    request.depot_program = depot_binary();
    const system::SystemRunResult run = system::run_system(
        system::load_system_spec(system::find_system_file(system::system_of_mode(mode))), request);
    const double ate =
        eval::compute_ate(eval::match_trajectories(read_tum_trajectory(data + "/groundtruth.txt"),
                                                   run.trajectory, {}, "gt", mode))
            .statistics.rmse;
    const double share = static_cast<double>(run.trajectory.size()) / run.frames;
    std::printf("%s %s: ATE %.4f m, tracked %.1f %%, %.0f ms per frame\n", GetParam().c_str(),
                mode.c_str(), ate, 100 * share, run.frame_ms);
    EXPECT_LT(ate, bounds["ate_max"].as<double>()) << mode << " ATE RMSE";
    EXPECT_GE(share, bounds["tracked_share_min"].as<double>()) << mode << " tracked share";
  }
}

// Generated halls (#27): each seed draws its own hall for
// depot_procedural_patrol; every one renders, is tracked by orb, full and
// masked within the bounds, and its dataset holds the hall it was drawn.
class ProceduralHalls : public ::testing::TestWithParam<int> {};

TEST_P(ProceduralHalls, EachSeedsHallRendersAndIsTrackedWithinTheBounds) {
  const YAML::Node b = YAML::LoadFile(kBounds)["procedural_halls"];
  ASSERT_TRUE(b) << "no procedural_halls bounds in " << kBounds;
  const std::string scenario = b["scenario"].as<std::string>();
  const int frames = b["frames"].as<int>();
  const std::string data = render_small(
      {scenario, frames, b["width"].as<int>(), false, static_cast<uint64_t>(GetParam())});
  // The hall it was drawn in, written out with the dataset (its seed named).
  const std::string hall = dataset::testing::read_text(data, "scene.yaml");
  EXPECT_NE(hall.find("procedural hall (world seed " + std::to_string(GetParam()) + ")"),
            std::string::npos);
  for (const auto& [mode, key] :
       {std::pair{slam::RejectionMode::kOrb, "orb"}, std::pair{slam::RejectionMode::kFull, "full"},
        std::pair{slam::RejectionMode::kMasked, "masked"}}) {
    const SlamOutcome run = run_slam_mode(data, mode, false);
    std::printf("%s seed %d %s: ATE %.4f m, tracked %.1f %%, lost %d\n", scenario.c_str(),
                GetParam(), key, run.ate_rmse, 100 * run.tracked_share(), run.lost);
    EXPECT_LT(run.ate_rmse, b[key]["ate_max"].as<double>()) << key << " ATE RMSE";
    EXPECT_GE(run.tracked_share(), b["tracked_share_min"].as<double>()) << key << " tracked";
    EXPECT_EQ(run.trajectory_size, run.tracked);
  }
}

INSTANTIATE_TEST_SUITE_P(Seeds, ProceduralHalls, ::testing::Range(1, 6),
                         [](const auto& info) { return "seed_" + std::to_string(info.param); });

INSTANTIATE_TEST_SUITE_P(Shipped, ScenarioRegression,
                         ::testing::Values("depot_walking_xyz", "depot_walking_halfsphere",
                                           "depot_walking_static", "depot_sitting_static",
                                           "depot_carry", "depot_crowd"),
                         [](const auto& info) { return info.param; });

}  // namespace
}  // namespace depot::test
