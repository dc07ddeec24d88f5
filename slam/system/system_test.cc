// What the system reports per frame: the trajectory holds tracked frames
// only, and frame_states() says what became of every frame given (here
// through a reset, on exact turned views of the real TUM frame).
#include "slam/system/system.h"

#include <filesystem>

#include <gtest/gtest.h>

#include "tests/support/real_frame.h"

namespace depot::slam {
namespace {

TEST(SystemStates, TheTrajectoryHoldsTrackedFramesOnlyAndEveryFrameHasAState) {
  if (!std::filesystem::exists(test::real_frame_folder()))
    GTEST_SKIP() << "shared data missing: " << test::real_frame_folder();
  const test::RealFrame real = test::load_real_frame();
  SlamSettings settings;  // TUM fr3, the frame's camera
  settings.threaded_mapping = false;
  System system(settings);
  const cv::Mat covered(real.bgr.size(), CV_8UC3, cv::Scalar::all(90));
  const cv::Mat no_depth(real.depth.size(), CV_32F, cv::Scalar(0));
  double t = 10.0;
  auto track_view = [&](double yaw) {
    const test::RealFrame v = test::turned_view(real, settings.camera, test::turn(yaw));
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

}  // namespace
}  // namespace depot::slam
