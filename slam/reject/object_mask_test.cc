// Depth segmentation inside a box on synthetic depth: a near object in front
// of far background splits right, the FAST-circle contact rule, and an
// object without depth gives no mask.
#include <gtest/gtest.h>

#include "slam/reject/object_mask.h"

namespace depot::slam {
namespace {

// A wall at 4 m; a "person" (torso 60x160 px at 1.5-1.66 m, leaning) with
// an arm reaching 40 px out towards the camera (1.55 -> 1.39 m, smoothly
// from the shoulder), and a shelf edge inside the box at 3 m.
cv::Mat scene_depth() {
  cv::Mat depth(240, 320, CV_32F, cv::Scalar(4.0f));
  for (int y = 40; y < 200; ++y)
    for (int x = 130; x < 190; ++x) depth.at<float>(y, x) = 1.5f + 0.001f * (y - 40);
  for (int y = 90; y < 100; ++y)
    for (int x = 90; x < 130; ++x) depth.at<float>(y, x) = 1.55f - 0.004f * (130 - x);
  for (int y = 150; y < 160; ++y)
    for (int x = 60; x < 100; ++x) depth.at<float>(y, x) = 3.0f;
  return depth;
}

TEST(ObjectMask, NearObjectSplitsFromFarBackground) {
  const cv::Mat depth = scene_depth();
  // A loose detector box, wider than the person, holding wall and shelf too.
  const ObjectMask m = segment_object(depth, cv::Rect2f(70, 30, 140, 180));
  ASSERT_TRUE(m.valid());
  EXPECT_NEAR(m.depth, 1.55f, 0.1f);
  EXPECT_TRUE(m.on_object(160, 100));   // torso
  EXPECT_TRUE(m.on_object(135, 195));   // torso's corner
  EXPECT_TRUE(m.on_object(95, 95));     // the arm, 0.15 m nearer than the torso
  EXPECT_FALSE(m.on_object(200, 100));  // wall inside the box
  EXPECT_FALSE(m.on_object(80, 155));   // shelf inside the box
  EXPECT_FALSE(m.on_object(160, 20));   // wall above the box
  // Every torso pixel is on the mask, no wall pixel is.
  int torso = 0, wall = 0;
  for (int y = 30; y < 210; ++y)
    for (int x = 70; x < 210; ++x) {
      const bool on = m.on_object(x, y);
      const bool truth =
          (y >= 40 && y < 200 && x >= 130 && x < 190) || (y >= 90 && y < 100 && x >= 90 && x < 130);
      torso += truth && on;
      wall += !truth && on;
    }
  EXPECT_EQ(torso, 160 * 60 + 10 * 40);
  EXPECT_EQ(wall, 0);
  const cv::Rect2f b = m.bounds();
  EXPECT_FLOAT_EQ(b.x, 90);
  EXPECT_FLOAT_EQ(b.width, 100);
}

TEST(ObjectMask, FindsTheObjectWhenTheBoxCentreIsBackground) {
  // A person cut by the image's edge: the box reaches past it over the wall.
  cv::Mat depth(240, 320, CV_32F, cv::Scalar(3.5f));
  for (int y = 20; y < 240; ++y)
    for (int x = 280; x < 320; ++x) depth.at<float>(y, x) = 1.2f;
  const ObjectMask m = segment_object(depth, cv::Rect2f(200, 20, 120, 220));
  ASSERT_TRUE(m.valid());
  EXPECT_NEAR(m.depth, 1.2f, 0.05f);
  EXPECT_TRUE(m.on_object(300, 100));
  EXPECT_FALSE(m.on_object(240, 100));
}

TEST(ObjectMask, ADepthEdgeStopsTheRegion) {
  // A cart 0.35 m behind the person (within the object's depth extent) that
  // touches it in the image: the depth edge between them keeps it out.
  cv::Mat depth(240, 320, CV_32F, cv::Scalar(4.0f));
  for (int y = 40; y < 200; ++y)
    for (int x = 130; x < 190; ++x) depth.at<float>(y, x) = 1.5f;
  for (int y = 120; y < 200; ++y)
    for (int x = 190; x < 230; ++x) depth.at<float>(y, x) = 1.85f;
  const ObjectMask m = segment_object(depth, cv::Rect2f(120, 30, 80, 180));
  ASSERT_TRUE(m.valid());
  EXPECT_TRUE(m.on_object(160, 150));
  EXPECT_FALSE(m.on_object(195, 150)) << "the cart inside the grown box";
  EXPECT_FALSE(m.on_object(200, 190));
}

TEST(ObjectMask, FastCircleContact) {
  const ObjectMask m = segment_object(scene_depth(), cv::Rect2f(70, 30, 140, 180));
  ASSERT_TRUE(m.valid());
  // Right edge of the torso at x = 189.
  EXPECT_TRUE(m.touches(cv::KeyPoint(188, 120, 7), 1.2f));   // on it
  EXPECT_TRUE(m.touches(cv::KeyPoint(192, 120, 7), 1.2f));   // 3 px out: the circle reaches
  EXPECT_FALSE(m.touches(cv::KeyPoint(194, 120, 7), 1.2f));  // 5 px out at level 0: no
  cv::KeyPoint coarse(194, 120, 7);
  coarse.octave = 3;  // radius 3 * 1.2^3 = 5.2 px
  EXPECT_TRUE(m.touches(coarse, 1.2f));
}

TEST(ObjectMask, NoDepthNoMask) {
  cv::Mat depth(240, 320, CV_32F, cv::Scalar(0.0f));
  EXPECT_FALSE(segment_object(depth, cv::Rect2f(100, 50, 80, 150)).valid());
  // A box entirely outside the image.
  EXPECT_FALSE(segment_object(scene_depth(), cv::Rect2f(400, 50, 80, 150)).valid());
}

// A seated person behind a desk and a monitor: wall at 4 m, the person
// (head and torso, 60x150 px) at 1.9-1.975 m, before them a monitor (100x70
// px at 1.2 m) over the person's middle and a desk edge (1.3-1.5 m) over the
// bottom, both wider than the person's box.
cv::Mat seated_depth() {
  cv::Mat depth(240, 320, CV_32F, cv::Scalar(4.0f));
  for (int y = 50; y < 200; ++y)
    for (int x = 130; x < 190; ++x) depth.at<float>(y, x) = 1.9f + 0.0005f * (y - 50);
  for (int y = 110; y < 180; ++y)
    for (int x = 110; x < 210; ++x) depth.at<float>(y, x) = 1.2f;
  for (int y = 180; y < 240; ++y)
    for (int x = 40; x < 280; ++x) depth.at<float>(y, x) = 1.5f - 0.0033f * (y - 180);
  return depth;
}

TEST(ObjectMask, AnOccluderBeforeTheObjectIsPassedOver) {
  const cv::Mat depth = seated_depth();
  const cv::Rect2f person(125, 48, 70, 180);
  ObjectMaskParams on;
  on.top_min_share = 0.1f;
  const ObjectMask m = segment_object(depth, person, on);
  ASSERT_TRUE(m.valid());
  EXPECT_NEAR(m.depth, 1.95f, 0.1f);
  EXPECT_TRUE(m.on_object(160, 60));    // head
  EXPECT_TRUE(m.on_object(140, 100));   // shoulder
  EXPECT_FALSE(m.on_object(160, 140));  // the monitor
  EXPECT_FALSE(m.on_object(160, 220));  // the desk
  EXPECT_FALSE(m.on_object(200, 60));   // wall
  // Without the occluder test the monitor, nearest, is taken for the person.
  ObjectMaskParams off;
  off.top_min_share = 0;
  EXPECT_NEAR(segment_object(depth, person, off).depth, 1.2f, 0.1f);
}

TEST(ObjectMask, AWallAboveAMisplacedBoxIsNoObject) {
  // A person (1.5 m) whose box starts 60 px above the head: the box's top is
  // wall, which also fills the search region around the box.
  cv::Mat depth(240, 320, CV_32F, cv::Scalar(4.0f));
  for (int y = 80; y < 240; ++y)
    for (int x = 130; x < 190; ++x) depth.at<float>(y, x) = 1.5f;
  ObjectMaskParams on;
  on.top_min_share = 0.1f;
  const ObjectMask m = segment_object(depth, cv::Rect2f(125, 20, 70, 220), on);
  ASSERT_TRUE(m.valid());
  EXPECT_NEAR(m.depth, 1.5f, 0.05f);
  EXPECT_TRUE(m.on_object(160, 150));
  EXPECT_FALSE(m.on_object(160, 50));
  // With no limit on the spill (nor on the gap), the wall is taken for the
  // object.
  ObjectMaskParams any_spill = on;
  any_spill.max_spill = 1.0f;
  any_spill.max_occluder_gap_m = 100.0f;
  EXPECT_NEAR(segment_object(depth, cv::Rect2f(125, 20, 70, 220), any_spill).depth, 4.0f, 0.05f);
}

TEST(ObjectMask, AnObjectFarBehindTheNearestIsNoOccludedObject) {
  // A walking person (1.5 m) whose box starts 60 px above the head, where a
  // crate stands 2 m further back (3.5 m) inside the box's top: it spills
  // little past the box, but a seated person sits just behind what hides
  // them, not metres behind.
  cv::Mat depth(240, 320, CV_32F, cv::Scalar(6.0f));
  for (int y = 20; y < 80; ++y)
    for (int x = 120; x < 200; ++x) depth.at<float>(y, x) = 3.5f;
  for (int y = 80; y < 240; ++y)
    for (int x = 130; x < 190; ++x) depth.at<float>(y, x) = 1.5f;
  const cv::Rect2f box(125, 20, 70, 220);
  ObjectMaskParams on;
  on.top_min_share = 0.1f;
  on.max_occluder_gap_m = 1.0f;
  const ObjectMask m = segment_object(depth, box, on);
  ASSERT_TRUE(m.valid());
  EXPECT_NEAR(m.depth, 1.5f, 0.05f);
  EXPECT_TRUE(m.on_object(160, 150));
  EXPECT_FALSE(m.on_object(160, 50));
  // With no limit on the gap, the crate is taken for the object.
  ObjectMaskParams any_gap = on;
  any_gap.max_occluder_gap_m = 100.0f;
  EXPECT_NEAR(segment_object(depth, box, any_gap).depth, 3.5f, 0.05f);
}

}  // namespace
}  // namespace depot::slam
