// The kidnapped robot (scenarios/depot_kidnapped.yaml, long tier, label
// scenario_long): the camera is covered for frames 1530-1634 of the two-lap
// patrol and reappears round a corner on the loop mapped in lap 1. Within
// 1 s of the cover lifting the camera must be back in the first map
// (relocalised, or in a new map merged into it), every uncovered frame
// (but for that second) must have a pose, and the ATE over all frames with a
// pose, each map aligned on its own, must stay within 2 cm.
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "slam/io/frame_states_file.h"
#include "tests/support/dataset_reader.h"
#include "tests/support/render_helpers.h"

namespace depot::test {
namespace {

constexpr int kFrames = 2095;
constexpr int kCoverFirst = 1530, kCoverLast = 1634;  // t in [51.0, 54.5) s at 30 Hz
constexpr int kSecond = 30;

void check_mode(const std::string& dataset, const std::string& mode) {
  SCOPED_TRACE(mode);
  const std::string run = temp_path("kidnapped") + ".txt";
  const DepotResult tracked =
      depot("slam run " + dataset + " -o " + run + " --mode " + mode + " --mapping sync -q");
  ASSERT_EQ(tracked.code, 0) << tracked.output;
  const std::vector<slam::StampedFrameState> states =
      slam::read_frame_states(slam::frame_states_path(run));
  ASSERT_EQ(states.size(), static_cast<size_t>(kFrames));

  int back = -1;  // the first frame after the cover in the first map (0)
  for (int i = kCoverLast + 1; i < kFrames && back < 0; ++i)
    if (states[i].map == 0) back = i;
  ASSERT_GE(back, 0) << "never back in the first map after the cover";
  EXPECT_LE(back - kCoverLast, kSecond) << "back in the first map at frame " << back;
  int posed = 0;
  for (int i = 0; i < kFrames; ++i) posed += states[i].map >= 0;
  const int uncovered = kFrames - (kCoverLast - kCoverFirst + 1);
  EXPECT_GE(posed, uncovered - kSecond)
      << posed << " of " << uncovered << " uncovered frames posed";

  const std::string json = temp_path("kidnapped_ate") + ".json";
  const DepotResult ate =
      depot("eval ate " + dataset + "/groundtruth.txt " + run + " --json " + json);
  ASSERT_EQ(ate.code, 0) << ate.output;
  std::ifstream in(json);
  const nlohmann::json report = nlohmann::json::parse(in);
  const double all_maps = report["all_maps"]["rmse"].get<double>();
  std::printf(
      "kidnapped %s: back at frame %d (%d after the cover), %d of %d uncovered frames "
      "posed, ATE over all maps %.4f m\n",
      mode.c_str(), back, back - kCoverLast, posed, uncovered, all_maps);
  EXPECT_LE(all_maps, 0.02);
}

// One render (1.5 min) for the three modes.
TEST(KidnappedRobot, IsBackInTheFirstMapWithinASecond) {
  const std::string dataset = render_small({"depot_kidnapped", kFrames, 640, false, 1});
  for (const char* mode : {"orb", "full", "masked"}) check_mode(dataset, mode);
}

}  // namespace
}  // namespace depot::test
