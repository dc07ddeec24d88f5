// The states file beside a trajectory: its name, its text, reading it back
// and the tracked share.
#include "slam/io/frame_states_file.h"

#include <filesystem>
#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/error.h"
#include "common/testing/temp_path.h"

namespace depot::slam {
namespace {

std::string temp_file(const std::string& name, const std::string& text) {
  // A folder of its own, so the file has exactly `name` (errors quote it).
  const std::filesystem::path dir = testkit::temp_path("states");
  std::filesystem::create_directories(dir);
  const std::string path = (dir / name).string();
  std::ofstream(path) << text;
  return path;
}

TEST(FrameStatesFile, SitsBesideTheTrajectory) {
  EXPECT_EQ(frame_states_path("out/run.txt"), "out/run.states.txt");
  EXPECT_EQ(frame_states_path("run.txt"), "run.states.txt");
  EXPECT_EQ(frame_states_path("out/run.tum"), "out/run.tum.states.txt");
  EXPECT_EQ(frame_states_path("run"), "run.states.txt");
}

TEST(FrameStatesFile, RoundTripsEveryState) {
  const std::vector<StampedFrameState> states = {{1.0, FrameState::kNotInitialized},
                                                 {1.1, FrameState::kAbandoned},
                                                 {1.2, FrameState::kLost},
                                                 {1.3, FrameState::kNewMap},
                                                 {1.4, FrameState::kOk},
                                                 {1.5, FrameState::kRelocalized}};
  const std::string text = format_frame_states(states, "test run");
  EXPECT_EQ(text.rfind("# test run\n# timestamp state", 0), 0u) << text;
  EXPECT_THAT(text, ::testing::HasSubstr("\n1.300000 NEW_MAP\n")) << text;
  const std::vector<StampedFrameState> back = read_frame_states(temp_file("all.txt", text));
  ASSERT_EQ(back.size(), states.size());
  for (size_t i = 0; i < states.size(); ++i) {
    EXPECT_DOUBLE_EQ(back[i].timestamp, states[i].timestamp);
    EXPECT_EQ(back[i].state, states[i].state);
  }
  const TrackedShare share = tracked_share(back);
  EXPECT_EQ(share.frames, 6u);
  EXPECT_EQ(share.tracked, 3u) << "NEW_MAP, OK and RELOCALIZED have poses";
  EXPECT_DOUBLE_EQ(share.share(), 0.5);
}

// The atlas: frames with a pose name their map; the atlas trajectory's
// lines follow them in order.
TEST(FrameStatesFile, FramesWithAPoseNameTheirMap) {
  EXPECT_EQ(atlas_trajectory_path("out/run.txt"), "out/run.atlas.txt");
  EXPECT_EQ(atlas_trajectory_path("run"), "run.atlas.txt");
  const std::vector<StampedFrameState> states = {
      {1.0, FrameState::kOtherMap, 1}, {1.1, FrameState::kOtherMap, 1},
      {1.2, FrameState::kLost, -1},    {1.3, FrameState::kNewMap, 0},
      {1.4, FrameState::kOk, 0},       {1.5, FrameState::kOtherMap, 2}};
  const std::string text = format_frame_states(states);
  EXPECT_THAT(text, ::testing::HasSubstr("\n1.200000 LOST\n1.300000 NEW_MAP 0\n")) << text;
  const std::vector<StampedFrameState> back = read_frame_states(temp_file("maps.txt", text));
  ASSERT_EQ(back.size(), states.size());
  for (size_t i = 0; i < states.size(); ++i) EXPECT_EQ(back[i].map, states[i].map) << i;
  EXPECT_EQ(maps_of_posed_frames(back), (std::vector<int>{1, 1, 0, 0, 2}));
  // A file of two columns (before the atlas, or another system's) names none.
  const std::vector<StampedFrameState> old =
      read_frame_states(temp_file("old.txt", "1.0 NEW_MAP\n1.1 OK\n"));
  EXPECT_EQ(old[1].map, -1);
  EXPECT_TRUE(maps_of_posed_frames(old).empty());
}

TEST(FrameStatesFile, BadLinesNameFileAndLine) {
  auto error_of = [](const std::string& text) {
    try {
      read_frame_states(temp_file("bad.txt", text));
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error_of("# c\n1.0 OK\n2.0 TRACKED\n").find("bad.txt:3: unknown state 'TRACKED'"),
            std::string::npos);
  EXPECT_NE(error_of("1.0 OK 0 extra\n").find("bad.txt:1: expected 2 or 3 fields"),
            std::string::npos);
  EXPECT_THAT(error_of("1.0\n"), ::testing::HasSubstr("bad.txt:1: expected 2 or 3 fields"));
  EXPECT_NE(error_of("1.0 LOST 0\n").find("bad.txt:1: a LOST frame has no pose, so no map"),
            std::string::npos);
  EXPECT_THAT(error_of("1.0 OK x\n"), ::testing::HasSubstr("bad.txt:1: 'x' is not a map number"));
  EXPECT_THAT(error_of("1.0 OK -1\n"), ::testing::HasSubstr("bad.txt:1: '-1' is not a map number"));
  EXPECT_NE(error_of("1.0 OK 2\n").find("bad.txt:1: a tracked frame is in map 0"),
            std::string::npos);
  EXPECT_NE(error_of("1.0 OTHER_MAP 0\n").find("bad.txt:1: an OTHER_MAP frame is not in map 0"),
            std::string::npos);
  EXPECT_THAT(error_of("x OK\n"), ::testing::HasSubstr("bad.txt:1: 'x' is not a timestamp"));
  EXPECT_NE(error_of("2.0 OK\n1.0 OK\n").find("bad.txt:2: timestamps must increase"),
            std::string::npos);
  EXPECT_THAT(error_of("# only a comment\n"), ::testing::HasSubstr("no frames"));
}

}  // namespace
}  // namespace depot::slam
