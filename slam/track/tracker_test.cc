// The tracker on exact turned views of the synthetic room (known poses):
// initialisation, the motion model, the reference-keyframe fallback, a lost
// frame (no pose) and recovery, and following points fused by mapping.
#include "slam/track/tracker.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "slam/feature/orb_extractor.h"
#include "slam/mapping/local_mapper.h"
#include "slam/place/keyframe_database.h"
#include "tests/support/real_frame.h"
#include "tests/support/room_vocabulary.h"
#include "tests/support/synthetic_room.h"

namespace depot::slam {
namespace {

// ORB-SLAM2's tracker (no atlas): most fixtures below test its states.
TrackerParams without_atlas() {
  TrackerParams p;
  p.atlas = false;
  return p;
}

class TrackerTest : public ::testing::Test {
 protected:
  void SetUp() override { real_ = test::room_frame(); }

  // Tracks the view turned by `yaw_deg` (synchronous mapping after it, as
  // System does) and checks its pose when tracked. Only the left
  // `depth_share` of the image keeps its depth (a depth gap: a wall closer
  // than the sensor's range, glass, sunlight).
  TrackingStats track_view(double yaw_deg, double depth_share = 1.0) {
    test::RealFrame view = test::room_view(test::turn(yaw_deg));
    const int keep = static_cast<int>(depth_share * view.depth.cols);
    view.depth.colRange(keep, view.depth.cols).setTo(0);
    TrackingStats stats;
    tracker_.track(make_frame(view.bgr, view.depth), &stats);
    mapper_.run_pending();
    if (tracker_.state() == TrackingState::kOk || tracker_.state() == TrackingState::kRelocalized)
      expect_pose(yaw_deg);
    return stats;
  }

  // A covered camera: nothing to see, no depth.
  TrackingStats track_covered() {
    TrackingStats stats;
    tracker_.track(make_frame(cv::Mat(real_.bgr.size(), CV_8UC3, cv::Scalar::all(90)),
                              cv::Mat(real_.depth.size(), CV_32F, cv::Scalar(0))),
                   &stats);
    mapper_.run_pending();
    return stats;
  }

  // The map's world is the camera of the frame it started on. A frame that
  // sees the map through a fifth of its view is held to a looser bound.
  void expect_pose(double yaw_deg, double max_error_deg = 0.1) {
    const Pose truth = test::turned_pose(test::turn(yaw_deg)) *
                       test::turned_pose(test::turn(map_start_yaw_)).inverse();
    const Pose& estimate = tracker_.last_frame().T_cw;
    EXPECT_LT(test::rotation_error_deg(estimate, truth), max_error_deg) << "yaw " << yaw_deg;
    EXPECT_LT(estimate.translation().norm(), 0.01) << "yaw " << yaw_deg;
  }

  Frame make_frame(const cv::Mat& bgr, const cv::Mat& depth) {
    cv::Mat gray;
    cv::cvtColor(bgr, gray, cv::COLOR_BGR2GRAY);
    std::vector<cv::KeyPoint> keypoints;
    cv::Mat descriptors;
    extractor_.extract(gray, cv::Mat(), keypoints, descriptors);
    const long id = next_id_++;
    return Frame(id, 1.0 + id / 30.0, Features(keypoints, descriptors, depth, camera_, &levels_));
  }

  std::vector<FrameState> states() const {
    std::vector<FrameState> out;
    for (const TrajectoryEntry& e : tracker_.trajectory()) out.push_back(e.state);
    return out;
  }

  test::RealFrame real_;
  PinholeCamera camera_;
  ScaleLevels levels_ = ScaleLevels::make(8, 1.2f);
  OrbExtractor extractor_{OrbParams{}};
  Map map_;
  KeyFrameDatabase places_{test::room_vocabulary()};
  LocalMapper mapper_{map_, false, &places_};
  // A place the map has never seen: the frame mirrored (ORB is not mirror
  // invariant, so nothing in the map matches it).
  TrackingStats track_mirrored() {
    cv::Mat bgr, depth;
    cv::flip(real_.bgr, bgr, 1);
    cv::flip(real_.depth, depth, 1);
    TrackingStats stats;
    tracker_.track(make_frame(bgr, depth), &stats);
    mapper_.run_pending();
    return stats;
  }

  // The parameters the next fixture's tracker gets (a derived fixture sets
  // them in SetUpTestSuite).
  static inline TrackerParams params_for_next_ = without_atlas();
  Tracker tracker_{map_, mapper_, params_for_next_, &places_};
  long next_id_ = 0;
  double map_start_yaw_ = 0;  // yaw of the view the current map started on
};

TEST_F(TrackerTest, StartsAMapThenFollowsTheCameraWithTheMotionModel) {
  EXPECT_EQ(track_view(0).method, TrackingMethod::kInitialization);
  EXPECT_EQ(tracker_.state(), TrackingState::kOk);
  EXPECT_EQ(map_.n_keyframes(), 1u);
  // No velocity yet after one frame: the reference keyframe.
  EXPECT_EQ(track_view(1).method, TrackingMethod::kReferenceKeyFrame);
  for (double yaw : {2.0, 3.0, 4.0, 5.0}) {
    const TrackingStats stats = track_view(yaw);
    EXPECT_EQ(stats.method, TrackingMethod::kMotionModel) << "yaw " << yaw;
    EXPECT_GT(stats.matches, 100) << "yaw " << yaw;
    EXPECT_EQ(tracker_.state(), TrackingState::kOk);
  }
  EXPECT_EQ(states(),
            (std::vector<FrameState>{FrameState::kNewMap, FrameState::kOk, FrameState::kOk,
                                     FrameState::kOk, FrameState::kOk, FrameState::kOk}));
}

// A map of one keyframe takes its second once the frame tracks few of its
// points (ORB-SLAM2's 40 % of the reference's), although those points are
// seen by one keyframe only. Here two thirds of the view are hidden.
TEST_F(TrackerTest, AOneKeyframeMapTakesASecondWhenFewOfItsPointsAreTracked) {
  track_view(0);
  ASSERT_EQ(map_.n_keyframes(), 1u);
  test::RealFrame partly = test::room_view(test::turn(1));
  const int cover = 2 * partly.bgr.cols / 3;
  partly.bgr.colRange(0, cover).setTo(cv::Scalar::all(90));
  partly.depth.colRange(0, cover).setTo(0);
  TrackingStats stats;
  tracker_.track(make_frame(partly.bgr, partly.depth), &stats);
  mapper_.run_pending();
  ASSERT_EQ(tracker_.state(), TrackingState::kOk);
  expect_pose(1);
  EXPECT_TRUE(stats.new_keyframe) << stats.inliers << " inliers";
  EXPECT_EQ(map_.n_keyframes(), 2u);
}

// Keypoints without depth still match map points and constrain the pose
// (two-dimensional residuals), so frames with no valid depth at all keep
// the camera tracked on the map made before the gap.
TEST_F(TrackerTest, TracksThroughFramesWithoutDepth) {
  track_view(0);
  track_view(1);
  const size_t keyframes = map_.n_keyframes();
  for (double yaw : {2.0, 3.0, 4.0, 5.0, 6.0}) {
    const TrackingStats stats = track_view(yaw, 0.0);
    EXPECT_EQ(tracker_.state(), TrackingState::kOk) << "yaw " << yaw;
    EXPECT_GT(stats.matches, 100) << "yaw " << yaw;
  }
  EXPECT_EQ(map_.n_keyframes(), keyframes) << "a frame without depth makes no keyframe";
  // Depth back: on as before.
  track_view(7);
  EXPECT_EQ(tracker_.state(), TrackingState::kOk);
}

// A gap over most of the image (only the left fifth has depth): tracked.
TEST_F(TrackerTest, TracksWithDepthOnlyInAStripOfTheImage) {
  track_view(0);
  for (double yaw : {1.0, 2.0, 3.0, 4.0, 5.0, 6.0}) {
    track_view(yaw, 0.2);
    EXPECT_EQ(tracker_.state(), TrackingState::kOk) << "yaw " << yaw;
  }
}

TEST_F(TrackerTest, FallsBackToTheReferenceKeyframeWhenTheMotionModelFails) {
  track_view(0);
  track_view(2);
  track_view(4);  // the motion model now predicts 6 degrees
  ASSERT_EQ(tracker_.state(), TrackingState::kOk);
  // The camera turned back instead: the prediction is 8 degrees (~75 px) off.
  const TrackingStats stats = track_view(-2);
  EXPECT_EQ(stats.method, TrackingMethod::kReferenceKeyFrame);
  EXPECT_EQ(tracker_.state(), TrackingState::kOk);
}

TEST_F(TrackerTest, ALostFrameHasNoPoseAndTheCameraIsFoundAgain) {
  track_view(0);
  track_view(1);
  track_view(2);
  track_covered();
  EXPECT_EQ(tracker_.state(), TrackingState::kLost);
  EXPECT_TRUE(tracker_.wants_reset())
      << "lost with a map of " << map_.n_keyframes() << " keyframes";
  const TrajectoryEntry& lost = tracker_.trajectory().back();
  EXPECT_EQ(lost.state, FrameState::kLost);
  EXPECT_EQ(lost.reference, nullptr) << "a lost frame is not a pose";
  // Still covered: still lost, and relocalisation is what it tries.
  EXPECT_EQ(track_covered().method, TrackingMethod::kRelocalization);
  EXPECT_EQ(tracker_.state(), TrackingState::kLost);
  // Uncovered where it was: relocalised at the right pose.
  EXPECT_EQ(track_view(1).method, TrackingMethod::kRelocalization);
  EXPECT_EQ(tracker_.state(), TrackingState::kRelocalized);
  EXPECT_FALSE(tracker_.wants_reset());
  track_view(1.5);
  EXPECT_EQ(tracker_.state(), TrackingState::kOk);
  EXPECT_EQ(states(), (std::vector<FrameState>{
                          FrameState::kNewMap, FrameState::kOk, FrameState::kOk, FrameState::kLost,
                          FrameState::kLost, FrameState::kRelocalized, FrameState::kOk}));
  for (const TrajectoryEntry& e : tracker_.trajectory())
    EXPECT_EQ(e.reference != nullptr, is_tracked(e.state));
}

TEST_F(TrackerTest, ResetAbandonsTheFramesOfTheOldMap) {
  track_view(0);
  track_view(1);
  track_covered();
  ASSERT_TRUE(tracker_.wants_reset());
  {
    MutexLock lock(map_.mutex());
    map_.clear();
    tracker_.reset();
  }
  EXPECT_FALSE(tracker_.wants_reset());
  EXPECT_EQ(tracker_.state(), TrackingState::kNotInitialized);
  map_start_yaw_ = 3;
  track_view(3);
  EXPECT_EQ(states(), (std::vector<FrameState>{FrameState::kAbandoned, FrameState::kAbandoned,
                                               FrameState::kLost, FrameState::kNewMap}));
  for (size_t i = 0; i < 3; ++i) EXPECT_EQ(tracker_.trajectory()[i].reference, nullptr);
}

TEST_F(TrackerTest, TheLastFrameFollowsPointsThatMappingFused) {
  track_view(0);
  track_view(1);
  // Local mapping fuses every point of the last frame into a twin (as when
  // it finds duplicates), between two frames.
  size_t fused = 0;
  {
    MutexLock lock(map_.mutex());
    for (MapPoint* mp : tracker_.last_frame().map_points) {
      if (!mp || mp->bad) continue;
      MapPoint* twin = map_.create_map_point(mp->position, mp->reference);
      mp->replace(twin);
      twin->update_normal_and_depth();
      ++fused;
    }
  }
  ASSERT_GT(fused, 200u);
  // The motion model matches the last frame's points: it must find the twins.
  const TrackingStats stats = track_view(2);
  EXPECT_EQ(stats.method, TrackingMethod::kMotionModel);
  EXPECT_GT(stats.matches, 100);
  for (MapPoint* mp : tracker_.last_frame().map_points) {
    if (mp) {
      EXPECT_FALSE(mp->bad);
    }
  }
}

// A young map lost for a while is reset; one lost for less, or one grown
// past young_map_keyframes, is not. The tiny-map rule is turned off here
// (reset_keyframes 0) so the young-map rule is seen alone.
class YoungMapTrackerTest : public TrackerTest {
 public:
  static void SetUpTestSuite() {
    params_for_next_.reset_keyframes = 0;
    params_for_next_.young_map_keyframes = 10;
    params_for_next_.young_map_lost_frames = 3;
  }
  static void TearDownTestSuite() { params_for_next_ = without_atlas(); }
};

TEST_F(YoungMapTrackerTest, AYoungMapLostForAWhileIsReset) {
  track_view(0);
  track_view(1);
  ASSERT_LT(map_.n_keyframes(), 10u);
  track_covered();
  track_covered();
  EXPECT_FALSE(tracker_.wants_reset()) << "lost for 2 frames only";
  track_view(1);  // found again: the count starts over
  ASSERT_EQ(tracker_.state(), TrackingState::kRelocalized);
  track_covered();
  track_covered();
  EXPECT_FALSE(tracker_.wants_reset());
  track_covered();
  EXPECT_TRUE(tracker_.wants_reset())
      << "lost 3 frames in a row in a map of " << map_.n_keyframes() << " keyframes";
}

// The same, with every map counted as grown (young_map_keyframes 1): lost
// for 5 frames, no reset.
class GrownMapTrackerTest : public TrackerTest {
 public:
  static void SetUpTestSuite() {
    params_for_next_.reset_keyframes = 0;
    params_for_next_.young_map_keyframes = 1;
    params_for_next_.young_map_lost_frames = 3;
  }
  static void TearDownTestSuite() { params_for_next_ = without_atlas(); }
};

// The weak-tracking rule alone: ORB-SLAM2's rules (weak_inliers 0) take no
// keyframe while the camera turns slowly over a well-seen map; with the bar
// above every frame's inliers, each tracked frame takes one.
class OrbSlam2KeyframesTest : public TrackerTest {
 public:
  static void SetUpTestSuite() { params_for_next_.weak_inliers = 0; }
  static void TearDownTestSuite() { params_for_next_ = without_atlas(); }
};
class WeakTrackingTest : public TrackerTest {
 public:
  static void SetUpTestSuite() { params_for_next_.weak_inliers = 100000; }
  static void TearDownTestSuite() { params_for_next_ = without_atlas(); }
};

TEST_F(OrbSlam2KeyframesTest, AWellTrackedFrameTakesNoKeyframe) {
  track_view(0);
  for (double yaw : {0.5, 1.0}) {
    const TrackingStats stats = track_view(yaw);
    EXPECT_FALSE(stats.new_keyframe) << "yaw " << yaw << ": " << stats.inliers << " inliers";
  }
  EXPECT_EQ(map_.n_keyframes(), 1u);
}

TEST_F(WeakTrackingTest, AFrameBelowTheInlierBarTakesAKeyframe) {
  track_view(0);
  for (double yaw : {0.5, 1.0}) {
    const TrackingStats stats = track_view(yaw);
    EXPECT_EQ(tracker_.state(), TrackingState::kOk);
    EXPECT_TRUE(stats.new_keyframe) << "yaw " << yaw << ": " << stats.inliers << " inliers";
  }
  EXPECT_EQ(map_.n_keyframes(), 3u);
}

TEST_F(GrownMapTrackerTest, AGrownMapIsNeverResetForBeingLost) {
  track_view(0);
  track_view(1);
  for (int k = 0; k < 5; ++k) track_covered();
  EXPECT_EQ(tracker_.state(), TrackingState::kLost);
  EXPECT_FALSE(tracker_.wants_reset());
}

// The atlas: a lost camera that cannot relocalise starts a new map at once
// and keeps the old one, which relocalisation still searches.
// The atlas with maps of one or two keyframes kept when lost (a real run
// discards maps that small; AtlasDiscardTest).
class AtlasTrackerTest : public TrackerTest {
 public:
  static void SetUpTestSuite() {
    params_for_next_.atlas = true;
    params_for_next_.reset_keyframes = 0;
  }
  static void TearDownTestSuite() { params_for_next_ = without_atlas(); }
};

// The atlas discarding a map lost while tiny (here: one keyframe).
class AtlasDiscardTest : public TrackerTest {
 public:
  static void SetUpTestSuite() {
    params_for_next_.atlas = true;
    params_for_next_.reset_keyframes = 1;
  }
  static void TearDownTestSuite() { params_for_next_ = without_atlas(); }

  // What System does when the tracker wants a reset.
  void discard_if_wanted() {
    if (!tracker_.wants_reset()) return;
    mapper_.reset();
    tracker_.discard_active_map();
  }
};

TEST_F(AtlasDiscardTest, ATinyLostMapIsForgottenAndTheOlderOneKept) {
  track_view(0);
  // Four fifths of the view hidden by a new, near textured surface: close
  // points the map lacks, so the frame becomes the map's second keyframe.
  test::RealFrame partly = test::room_view(test::turn(1));
  const int cover = 4 * partly.bgr.cols / 5;
  cv::Mat texture(partly.bgr.rows, cover, CV_8UC3);
  cv::RNG rng(7);
  rng.fill(texture, cv::RNG::UNIFORM, 0, 256);
  cv::GaussianBlur(texture, texture, cv::Size(3, 3), 0);
  texture.copyTo(partly.bgr.colRange(0, cover));
  partly.depth.colRange(0, cover).setTo(1.2);
  tracker_.track(make_frame(partly.bgr, partly.depth));
  mapper_.run_pending();
  expect_pose(1, 0.2);
  track_view(2);
  const size_t first_map_keyframes = map_.n_keyframes_in(0);
  ASSERT_GE(first_map_keyframes, 2u) << "the first map must outgrow reset_keyframes";
  track_covered();
  EXPECT_FALSE(tracker_.wants_reset()) << "a map of " << first_map_keyframes << " keyframes stays";
  ASSERT_EQ(track_mirrored().method, TrackingMethod::kInitialization);
  ASSERT_EQ(map_.active_map(), 1);
  KeyFrame* tiny = map_.first_keyframe_in(1);
  track_covered();
  ASSERT_TRUE(tracker_.wants_reset()) << "a one-keyframe map lost";
  discard_if_wanted();
  EXPECT_TRUE(tiny->bad);
  EXPECT_EQ(map_.map_ids(), (std::vector<int>{0}));
  EXPECT_EQ(map_.n_keyframes_in(0), first_map_keyframes);
  EXPECT_EQ(tracker_.state(), TrackingState::kLost) << "other maps are left to relocalise in";
  // The forgotten map's place is new again: a new map starts there (its
  // keyframe left place recognition with it).
  EXPECT_EQ(track_mirrored().method, TrackingMethod::kInitialization);
  EXPECT_EQ(map_.active_map(), 2);
  std::vector<FrameState> expected(3, FrameState::kOk);
  expected[0] = FrameState::kNewMap;
  for (FrameState s :
       {FrameState::kLost, FrameState::kAbandoned, FrameState::kLost, FrameState::kNewMap})
    expected.push_back(s);
  EXPECT_EQ(states(), expected);
}

TEST_F(AtlasTrackerTest, ALostCameraStartsANewMapAndFindsTheOldOneAgain) {
  track_view(0);
  track_view(1);
  const size_t first_map_keyframes = map_.n_keyframes_in(0);
  ASSERT_GE(first_map_keyframes, 1u);
  track_covered();
  EXPECT_EQ(tracker_.state(), TrackingState::kLost);
  EXPECT_FALSE(tracker_.wants_reset()) << "reset_keyframes 0: no map is discarded";
  // Still covered: nothing to start a map on.
  EXPECT_EQ(track_covered().method, TrackingMethod::kRelocalization);
  EXPECT_EQ(tracker_.state(), TrackingState::kLost);
  // A place no map knows: a new map starts on this frame.
  EXPECT_EQ(track_mirrored().method, TrackingMethod::kInitialization);
  EXPECT_EQ(tracker_.state(), TrackingState::kOk);
  EXPECT_EQ(map_.active_map(), 1);
  EXPECT_EQ(map_.n_keyframes_in(1), 1u);
  EXPECT_EQ(map_.n_keyframes_in(0), first_map_keyframes) << "the old map is kept";
  EXPECT_TRUE(map_.first_keyframe_in(1)->map_origin);
  // Lost again, then back where the first map was made: relocalised in it
  // (at the right pose, track_view checks), and tracking goes on there.
  track_covered();
  map_start_yaw_ = 0;
  EXPECT_EQ(track_view(1).method, TrackingMethod::kRelocalization);
  EXPECT_EQ(tracker_.state(), TrackingState::kRelocalized);
  EXPECT_EQ(map_.active_map(), 0);
  track_view(2);
  EXPECT_EQ(tracker_.state(), TrackingState::kOk);
  EXPECT_EQ(states(),
            (std::vector<FrameState>{FrameState::kNewMap, FrameState::kOk, FrameState::kLost,
                                     FrameState::kLost, FrameState::kNewMap, FrameState::kLost,
                                     FrameState::kRelocalized, FrameState::kOk}));
}

// A young map rejoins the older one as soon as a frame tracked in it also
// relocalises there. The frame: its left half from the mirrored place the
// young map started on, its right half from the first map's place (the view
// at yaw 0, while the first map started at yaw 5, so the maps' frames differ
// by a 5 degree turn).
TEST_F(AtlasTrackerTest, AYoungMapRejoinsTheOlderOneWhenAFrameRelocalisesThere) {
  map_start_yaw_ = 5;
  track_view(5);
  track_view(6);
  track_covered();
  track_covered();
  ASSERT_EQ(track_mirrored().method, TrackingMethod::kInitialization);
  ASSERT_EQ(map_.active_map(), 1);
  KeyFrame* young_origin = map_.first_keyframe_in(1);
  const Pose young_origin_before = young_origin->T_cw;
  cv::Mat mirrored_bgr, mirrored_depth;
  cv::flip(real_.bgr, mirrored_bgr, 1);
  cv::flip(real_.depth, mirrored_depth, 1);
  const test::RealFrame view0 = test::room_view(test::turn(0));
  const int half = real_.bgr.cols / 2;
  cv::Mat bgr = mirrored_bgr.clone(), depth = mirrored_depth.clone();
  view0.bgr.colRange(half, bgr.cols).copyTo(bgr.colRange(half, bgr.cols));
  view0.depth.colRange(half, depth.cols).copyTo(depth.colRange(half, depth.cols));
  TrackingStats stats;
  tracker_.track(make_frame(bgr, depth), &stats);
  mapper_.run_pending();
  EXPECT_EQ(tracker_.state(), TrackingState::kOk);
  EXPECT_EQ(tracker_.rejoined(), 1);
  EXPECT_EQ(map_.active_map(), 0);
  EXPECT_EQ(map_.map_ids(), (std::vector<int>{0}));
  EXPECT_EQ(young_origin->map_id, 0);
  EXPECT_FALSE(young_origin->map_origin);
  // The frame is where the view at yaw 0 is in the first map (tracked on
  // that map's points now), and the young map moved by the maps' turn.
  expect_pose(0);
  const Pose turn_between =
      test::turned_pose(test::turn(0)) * test::turned_pose(test::turn(5)).inverse();
  EXPECT_LT(test::rotation_error_deg(young_origin->T_cw, young_origin_before * turn_between), 0.2);
  EXPECT_EQ(states().back(), FrameState::kOk);
}

}  // namespace
}  // namespace depot::slam
