// Map reuse on a rendered depot (320x240): a map saved and loaded
// localises exactly as the map in memory, localisation adds nothing to the
// map, and finds the camera as well as mapping did.
#include <filesystem>
#include <fstream>
#include <mutex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/error.h"
#include "common/testing/temp_path.h"
#include "eval/ate.h"
#include "eval/matched_trajectories.h"
#include "slam/data/map.h"
#include "slam/io/map_file.h"
#include "slam/io/settings.h"
#include "slam/io/tum_sequence.h"
#include "slam/system/system.h"
#include "tests/support/render_helpers.h"

namespace depot::test {
namespace {

const std::string& depot_static() {
  static const std::string d = render_small(SmallRender("depot_static", 300, 320, false, 1));
  return d;
}

struct Pass {
  std::vector<slam::TrackingState> states;
  std::vector<Pose> poses;  // T_wc, identity when not tracked
};

// Every frame of the sequence once more, 1000 s later.
Pass localise(slam::System& system, slam::TumSequence& sequence) {
  Pass pass;
  cv::Mat bgr, depth;
  for (size_t i = 0; i < sequence.size(); ++i) {
    sequence.load(i, bgr, depth);
    const slam::TrackResult r = system.track(bgr, depth, sequence.entry(i).rgb_timestamp + 1000);
    pass.states.push_back(r.state);
    pass.poses.push_back(r.T_wc);
  }
  system.finish();
  return pass;
}

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

bool tracked(slam::TrackingState s) {
  return s == slam::TrackingState::kOk || s == slam::TrackingState::kRelocalized;
}

TEST(SlamMap, ASavedMapLocalisesExactlyAsTheMapInMemory) {
  slam::TumSequence sequence(depot_static());
  slam::SlamSettings settings = slam::load_settings(sequence.calibration_path());
  settings.threaded_mapping = false;  // reproducible
  sequence.set_depth_factor(settings.camera.depth_factor);
  const std::string map_path = testkit::temp_path("slam_map_test") + ".map";

  // Map the sequence, keep the poses mapping gave, save.
  slam::System mapper(settings);
  cv::Mat bgr, depth;
  for (size_t i = 0; i < sequence.size(); ++i) {
    sequence.load(i, bgr, depth);
    mapper.track(bgr, depth, sequence.entry(i).rgb_timestamp);
  }
  mapper.finish();
  const std::vector<StampedPose> mapped = mapper.trajectory();
  mapper.save_map(map_path);
  const size_t keyframes = mapper.n_keyframes();
  // What the file holds: the points keyframes observe (none of the points
  // whose observations were culled).
  slam::Map saved_map;
  slam::ScaleLevels saved_levels;
  size_t points = 0;
  {
    MutexLock lock(saved_map.mutex());
    points = slam::load_map_file_as_saved(map_path, saved_levels, saved_map).points;
    for (const slam::MapPoint* mp : saved_map.map_points())
      EXPECT_GT(mp->n_observations(), 0) << "point " << mp->id << " is saved but unobserved";
  }
  EXPECT_LE(points, mapper.n_map_points());

  // Localise again in the map in memory, and in the map loaded from the file.
  mapper.start_localisation();
  const Pass in_memory = localise(mapper, sequence);
  slam::System loaded(settings);
  loaded.load_map(map_path);
  EXPECT_EQ(loaded.n_keyframes(), keyframes);
  EXPECT_EQ(loaded.n_map_points(), points);
  // Localisation leaves the map as it was, to the byte: the points'
  // visible/found counters included (the loaded map saved before and after).
  const std::string before = map_path + ".before", after = map_path + ".after";
  loaded.save_map(before);
  loaded.start_localisation();
  const Pass from_file = localise(loaded, sequence);
  loaded.save_map(after);
  EXPECT_EQ(read_bytes(after), read_bytes(before)) << "localisation changed the loaded map";
  for (const std::string& p : {before, after, map_path}) std::filesystem::remove(p);

  // Localisation changed neither map.
  EXPECT_EQ(mapper.n_keyframes(), keyframes);
  EXPECT_EQ(loaded.n_keyframes(), keyframes);
  EXPECT_EQ(loaded.n_map_points(), points);
  // The first frame relocalises; the two runs are the same, frame by frame.
  EXPECT_EQ(from_file.states.front(), slam::TrackingState::kRelocalized);
  ASSERT_EQ(in_memory.states, from_file.states);
  int n_tracked = 0;
  double max_difference = 0;
  std::vector<StampedPose> localised;
  for (size_t i = 0; i < sequence.size(); ++i) {
    if (!tracked(from_file.states[i])) continue;
    ++n_tracked;
    max_difference =
        std::max(max_difference,
                 (in_memory.poses[i].matrix() - from_file.poses[i].matrix()).cwiseAbs().maxCoeff());
    localised.push_back({sequence.entry(i).rgb_timestamp, from_file.poses[i]});
  }
  // Against the truth, as the mapping pass is.
  const auto gt = read_tum_trajectory(depot_static() + "/groundtruth.txt");
  auto ate = [&](const std::vector<StampedPose>& t) {
    return eval::compute_ate(eval::match_trajectories(gt, t, {}, "gt", "estimate")).statistics.rmse;
  };
  const double ate_localised = ate(localised), ate_mapped = ate(mapped);
  std::printf(
      "map of %zu keyframes, %zu points: %d of %zu frames localised; loaded vs in memory %.2g; "
      "ATE localised %.4f m, mapping pass %.4f m\n",
      keyframes, points, n_tracked, sequence.size(), max_difference, ate_localised, ate_mapped);
  EXPECT_EQ(max_difference, 0.0);
  EXPECT_GE(n_tracked, static_cast<int>(0.95 * sequence.size()));
  EXPECT_LT(ate_localised, 0.03);
}

TEST(SlamMap, LocalisationNeedsAMap) {
  slam::TumSequence sequence(depot_static());
  slam::SlamSettings settings = slam::load_settings(sequence.calibration_path());
  slam::System system(settings);
  EXPECT_THROW(system.start_localisation(), Error);
}

}  // namespace
}  // namespace depot::test
