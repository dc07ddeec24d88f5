// Missed-detection recovery: a box missed for up to max_missed frames is
// carried by its velocity and then dropped; a re-detection continues its track.
#include <gtest/gtest.h>

#include "slam/reject/box_tracker.h"

namespace depot::slam {
namespace {

Detection person_at(float x) {
  Detection d;
  d.class_name = "person";
  d.confidence = 0.8f;
  d.box = cv::Rect2f(x, 50, 60, 150);
  return d;
}

TEST(BoxTracker, BridgesAMissForKFramesThenDrops) {
  BoxTrackerParams params;
  params.max_missed = 3;
  BoxTracker tracker(params);
  int id = 0;
  for (int f = 0; f < 4; ++f) {  // walking right at 8 px per frame
    const auto boxes = tracker.update({person_at(100 + 8.0f * f)});
    ASSERT_EQ(boxes.size(), 1u);
    EXPECT_EQ(boxes[0].missed, 0);
    if (f == 0) id = boxes[0].track_id;
    EXPECT_EQ(boxes[0].track_id, id);
  }
  for (int f = 4; f < 7; ++f) {  // missed: carried where the person would be
    const auto boxes = tracker.update({});
    ASSERT_EQ(boxes.size(), 1u) << "frame " << f;
    EXPECT_EQ(boxes[0].track_id, id);
    EXPECT_EQ(boxes[0].missed, f - 3);
    EXPECT_NEAR(boxes[0].detection.box.x, 100 + 8.0f * f, 0.5f);
    EXPECT_EQ(boxes[0].detection.class_name, "person");
  }
  EXPECT_TRUE(tracker.update({}).empty());  // the 4th miss: dropped
  EXPECT_EQ(tracker.tracks(), 0u);
}

// A carried box whose object the caller keeps finding (correct()) lives up
// to max_missed_seen frames; one frame without it and max_missed holds again.
// A measured motion (the object's flow) moves the box in place of the
// detections' velocity for one update: a camera that turned the other way.
TEST(BoxTracker, AMeasuredMotionMovesTheBoxInsteadOfItsVelocity) {
  BoxTracker tracker;
  int id = 0;
  for (int f = 0; f < 3; ++f) id = tracker.update({person_at(100 + 8.0f * f)})[0].track_id;
  tracker.set_motion(id, {-20, 5});
  auto boxes = tracker.update({});
  ASSERT_EQ(boxes.size(), 1u);
  EXPECT_NEAR(boxes[0].detection.box.x, 116 - 20, 0.5f);
  EXPECT_NEAR(boxes[0].detection.box.y, 50 + 5, 0.5f);
  boxes = tracker.update({});  // no measurement: the velocity again
  ASSERT_EQ(boxes.size(), 1u);
  EXPECT_NEAR(boxes[0].detection.box.x, 96 + 8, 0.5f);
  // A detection where the measured motion took the object matches its track.
  tracker.set_motion(id, {-30, 0});
  boxes = tracker.update({person_at(60)});  // 14 px off the measured place, 52 off the velocity's
  ASSERT_EQ(boxes.size(), 1u);
  EXPECT_EQ(boxes[0].track_id, id);
  EXPECT_EQ(boxes[0].missed, 0);
}

TEST(BoxTracker, ACarriedBoxStillSeenLivesLonger) {
  BoxTrackerParams params;
  params.max_missed = 2;
  params.max_missed_seen = 6;
  BoxTracker tracker(params);
  tracker.update({person_at(100)});
  const int id = tracker.update({person_at(104)})[0].track_id;
  for (int miss = 1; miss <= 6; ++miss) {
    const auto boxes = tracker.update({});
    ASSERT_EQ(boxes.size(), 1u) << "miss " << miss;
    EXPECT_EQ(boxes[0].track_id, id);
    EXPECT_EQ(boxes[0].missed, miss);
    tracker.correct(id, boxes[0].detection.box);  // its object found where carried
  }
  EXPECT_TRUE(tracker.update({}).empty()) << "past max_missed_seen";

  // Found while carried, then not: dropped at max_missed.
  BoxTracker again(params);
  again.update({person_at(100)});
  const int other = again.update({person_at(104)})[0].track_id;
  again.correct(other, again.update({})[0].detection.box);  // miss 1, seen
  ASSERT_EQ(again.update({}).size(), 1u);                   // miss 2, not seen
  EXPECT_TRUE(again.update({}).empty()) << "miss 3 > max_missed without its object";
}

TEST(BoxTracker, RedetectionContinuesTheTrack) {
  BoxTracker tracker;
  const int id = tracker.update({person_at(100)})[0].track_id;
  tracker.update({person_at(110)});
  tracker.update({});  // one miss
  const auto boxes = tracker.update({person_at(130)});
  ASSERT_EQ(boxes.size(), 1u);
  EXPECT_EQ(boxes[0].track_id, id);
  EXPECT_EQ(boxes[0].missed, 0);
  // A detection of another class far away starts a new track; the person's
  // track is carried beside it.
  Detection dog = person_at(400);
  dog.class_name = "dog";
  const auto two = tracker.update({dog});
  ASSERT_EQ(two.size(), 2u);
  EXPECT_NE(two[0].track_id, id);
  EXPECT_EQ(two[1].track_id, id);
  EXPECT_EQ(two[1].missed, 1);
}

TEST(BoxTracker, ABoxSeenOnceIsNotCarried) {
  // A false detection lasts one frame; with min_hits 2 its box is not
  // carried over the frames after it, but a person detected every other
  // frame (the track is kept to match) is carried from the second hit on.
  BoxTrackerParams params;
  params.min_hits = 2;
  BoxTracker tracker(params);
  const int id = tracker.update({person_at(100)})[0].track_id;
  EXPECT_TRUE(tracker.update({}).empty());  // seen once: not carried
  EXPECT_EQ(tracker.tracks(), 1u);          // but kept to match
  const auto again = tracker.update({person_at(116)});
  ASSERT_EQ(again.size(), 1u);
  EXPECT_EQ(again[0].track_id, id);
  const auto carried = tracker.update({});  // seen twice: carried
  ASSERT_EQ(carried.size(), 1u);
  EXPECT_EQ(carried[0].track_id, id);
  EXPECT_EQ(carried[0].missed, 1);
}

TEST(BoxTracker, CorrectionMovesACarriedBox) {
  BoxTracker tracker;
  const int id = tracker.update({person_at(100)})[0].track_id;
  tracker.update({person_at(100)});  // seen twice, standing still
  tracker.update({});
  tracker.correct(id, cv::Rect2f(90, 50, 60, 150));
  const auto boxes = tracker.update({});
  ASSERT_EQ(boxes.size(), 1u);
  EXPECT_FLOAT_EQ(boxes[0].detection.box.x, 90);  // no velocity yet: stays where corrected
}

TEST(BoxTracker, ACarriedBoxKeepsItsObjectsDepth) {
  BoxTracker tracker;
  const auto first = tracker.update({person_at(100)});
  EXPECT_EQ(first[0].depth, 0.0f);  // nothing recorded yet
  tracker.set_depth(first[0].track_id, 2.4f);
  tracker.update({person_at(100)});  // seen twice: carried when missed
  const auto carried = tracker.update({});
  ASSERT_EQ(carried.size(), 1u);
  EXPECT_EQ(carried[0].missed, 1);
  EXPECT_FLOAT_EQ(carried[0].depth, 2.4f);
}

}  // namespace
}  // namespace depot::slam
