// What the system reports per frame: the trajectory holds tracked frames
// only, and frame_states() says what became of every frame given (here
// through a reset, on exact turned views of the synthetic room).
#include "slam/system/system.h"

#include <gtest/gtest.h>

#include "tests/support/real_frame.h"
#include "tests/support/room_vocabulary.h"
#include "tests/support/synthetic_room.h"

namespace depot::slam {
namespace {

TEST(SystemStates, TheTrajectoryHoldsTrackedFramesOnlyAndEveryFrameHasAState) {
  const test::RealFrame real = test::room_frame();
  SlamSettings settings;  // TUM fr3, the frame's camera
  settings.vocabulary = test::room_vocabulary_file();
  settings.threaded_mapping = false;
  settings.tracker.atlas = false;  // ORB-SLAM2: young maps are reset
  System system(settings);
  const cv::Mat covered(real.bgr.size(), CV_8UC3, cv::Scalar::all(90));
  const cv::Mat no_depth(real.depth.size(), CV_32F, cv::Scalar(0));
  double t = 10.0;
  auto track_view = [&](double yaw) {
    const test::RealFrame v = test::room_view(test::turn(yaw));
    return system.track(v.bgr, v.depth, t += 0.1).state;
  };
  auto track_covered = [&] { return system.track(covered, no_depth, t += 0.1).state; };

  EXPECT_EQ(track_view(0), TrackingState::kOk);
  EXPECT_EQ(track_view(1), TrackingState::kOk);
  // Lost two frames into the map: the system starts a new one.
  EXPECT_EQ(track_covered(), TrackingState::kLost);
  EXPECT_EQ(system.resets(), 1);
  EXPECT_EQ(track_covered(), TrackingState::kNotInitialized);
  EXPECT_EQ(track_view(2), TrackingState::kOk);
  EXPECT_EQ(track_view(3), TrackingState::kOk);
  EXPECT_EQ(track_view(4), TrackingState::kOk);
  system.finish();

  const std::vector<StampedFrameState> states = system.frame_states();
  const std::vector<FrameState> expected = {FrameState::kAbandoned, FrameState::kAbandoned,
                                            FrameState::kLost,      FrameState::kNotInitialized,
                                            FrameState::kNewMap,    FrameState::kOk,
                                            FrameState::kOk};
  ASSERT_EQ(states.size(), expected.size());
  for (size_t i = 0; i < states.size(); ++i) {
    EXPECT_EQ(states[i].state, expected[i])
        << "frame " << i << ": " << frame_state_name(states[i].state);
    EXPECT_DOUBLE_EQ(states[i].timestamp, 10.0 + 0.1 * (i + 1));
  }
  // The trajectory: the frames of the new map, in its coordinates (the
  // frame it started on is the origin).
  const std::vector<StampedPose> trajectory = system.trajectory();
  ASSERT_EQ(trajectory.size(), 3u);
  for (size_t k = 0; k < 3; ++k) {
    EXPECT_DOUBLE_EQ(trajectory[k].timestamp, states[4 + k].timestamp);
    const Pose truth =
        (test::turned_pose(test::turn(2 + k)) * test::turned_pose(test::turn(2)).inverse())
            .inverse();
    EXPECT_LT(test::rotation_error_deg(trajectory[k].pose, truth), 0.1) << "frame " << 4 + k;
    EXPECT_LT(trajectory[k].pose.translation().norm(), 0.01) << "frame " << 4 + k;
  }
}

// The atlas: frames tracked in a map that never joins the main one are
// OTHER_MAP and stay out of the trajectory, which is in the main map's frame.
TEST(SystemStates, FramesOfAnotherMapOfTheAtlasAreNamedAndLeftOut) {
  const test::RealFrame real = test::room_frame();
  SlamSettings settings;
  settings.vocabulary = test::room_vocabulary_file();
  settings.threaded_mapping = false;
  settings.tracker.reset_keyframes = 0;  // keep maps of one or two keyframes
  System system(settings);
  const cv::Mat covered(real.bgr.size(), CV_8UC3, cv::Scalar::all(90));
  const cv::Mat no_depth(real.depth.size(), CV_32F, cv::Scalar(0));
  cv::Mat mirrored_bgr, mirrored_depth;  // a place the first map never saw
  cv::flip(real.bgr, mirrored_bgr, 1);
  cv::flip(real.depth, mirrored_depth, 1);
  double t = 10.0;
  auto track_view = [&](double yaw) {
    const test::RealFrame v = test::room_view(test::turn(yaw));
    return system.track(v.bgr, v.depth, t += 0.1).state;
  };
  EXPECT_EQ(track_view(0), TrackingState::kOk);
  EXPECT_EQ(track_view(1), TrackingState::kOk);
  EXPECT_EQ(system.track(covered, no_depth, t += 0.1).state, TrackingState::kLost);
  EXPECT_EQ(system.track(mirrored_bgr, mirrored_depth, t += 0.1).state, TrackingState::kOk);
  EXPECT_EQ(system.track(mirrored_bgr, mirrored_depth, t += 0.1).state, TrackingState::kOk);
  EXPECT_EQ(system.track(covered, no_depth, t += 0.1).state, TrackingState::kLost);
  EXPECT_EQ(track_view(2), TrackingState::kRelocalized);
  EXPECT_EQ(track_view(3), TrackingState::kOk);
  EXPECT_EQ(track_view(4), TrackingState::kOk);
  system.finish();
  EXPECT_EQ(system.resets(), 0);
  EXPECT_EQ(system.maps(), 2);

  const std::vector<FrameState> expected = {
      FrameState::kNewMap,      FrameState::kOk,       FrameState::kLost,
      FrameState::kOtherMap,    FrameState::kOtherMap, FrameState::kLost,
      FrameState::kRelocalized, FrameState::kOk,       FrameState::kOk};
  const std::vector<StampedFrameState> states = system.frame_states();
  ASSERT_EQ(states.size(), expected.size());
  for (size_t i = 0; i < states.size(); ++i)
    EXPECT_EQ(states[i].state, expected[i])
        << "frame " << i << ": " << frame_state_name(states[i].state);
  // The trajectory: the main map's five frames, in its frame (view 0 is the origin).
  const std::vector<StampedPose> trajectory = system.trajectory();
  const std::vector<double> yaws = {0, 1, 2, 3, 4};
  ASSERT_EQ(trajectory.size(), yaws.size());
  for (size_t k = 0; k < yaws.size(); ++k) {
    const Pose truth =
        (test::turned_pose(test::turn(yaws[k])) * test::turned_pose(test::turn(0)).inverse())
            .inverse();
    EXPECT_LT(test::rotation_error_deg(trajectory[k].pose, truth), 0.1) << "yaw " << yaws[k];
    EXPECT_LT(trajectory[k].pose.translation().norm(), 0.01) << "yaw " << yaws[k];
  }
  // Every frame with a pose, each in its own map: the main map is 0.
  const std::vector<AtlasPose> atlas = system.atlas_trajectory();
  ASSERT_EQ(atlas.size(), 7u);
  std::vector<int> maps;
  for (const AtlasPose& p : atlas) maps.push_back(p.map);
  EXPECT_EQ(maps, (std::vector<int>{0, 0, 1, 1, 0, 0, 0}));
  for (const StampedFrameState& s : states)
    EXPECT_EQ(s.map, s.state == FrameState::kOtherMap ? 1 : is_tracked(s.state) ? 0 : -1);
  // The mirrored place's frames are where that map put them: its first
  // frame is its origin.
  EXPECT_LT(atlas[2].pose.pose.translation().norm(), 1e-9);
  // Keyframes by map: the mirrored place's first frame began map 1.
  const std::vector<std::vector<StampedPose>> keyframes = system.keyframe_trajectories();
  ASSERT_EQ(keyframes.size(), 2u);
  ASSERT_FALSE(keyframes[1].empty());
  EXPECT_DOUBLE_EQ(keyframes[1].front().timestamp, states[3].timestamp);
  for (const StampedPose& k : keyframes[0]) EXPECT_NE(k.timestamp, states[3].timestamp);
  EXPECT_EQ(system.keyframe_trajectory().size(), keyframes[0].size());
}

}  // namespace
}  // namespace depot::slam
