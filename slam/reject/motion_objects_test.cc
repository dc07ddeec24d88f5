#include "slam/reject/motion_objects.h"

#include <gtest/gtest.h>

namespace depot::slam {
namespace {

const cv::Size kImage(640, 480);

// A grid of keypoints over the image at `depth`, all static.
std::vector<TestedKeypoint> static_scene(float depth) {
  std::vector<TestedKeypoint> tested;
  for (int y = 10; y < kImage.height; y += 20)
    for (int x = 10; x < kImage.width; x += 20)
      tested.push_back({cv::Point2f(static_cast<float>(x), static_cast<float>(y)), depth, false});
  return tested;
}

// Marks the keypoints inside `area` moving and puts them at `depth`.
void place_mover(std::vector<TestedKeypoint>& tested, const cv::Rect2f& area, float depth) {
  for (TestedKeypoint& k : tested)
    if (area.contains(k.pixel)) k.moving = true, k.depth = depth;
}

TEST(MotionObjects, FindsAGroupOfMovingKeypointsAtOneDepth) {
  std::vector<TestedKeypoint> tested = static_scene(4.0f);
  const cv::Rect2f animal(300, 300, 100, 60);
  place_mover(tested, animal, 2.0f);
  const std::vector<MotionObject> found = find_motion_objects(tested, kImage, {});
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].seeds, 15);  // 5 x 3 grid points inside
  EXPECT_EQ(found[0].tested, 15);
  EXPECT_FLOAT_EQ(found[0].depth, 2.0f);
  // The search box holds the animal and stays near it.
  EXPECT_FLOAT_EQ((found[0].box & animal).area(), animal.area());
  EXPECT_LT(found[0].box.area(), 4.0f * 200 * 160);
}

TEST(MotionObjects, ScatteredSlipsAreNoObject) {
  std::vector<TestedKeypoint> tested = static_scene(3.0f);
  // Every 7th keypoint fails: a slip here and there, never a group.
  for (size_t i = 0; i < tested.size(); i += 7) tested[i].moving = true;
  EXPECT_TRUE(find_motion_objects(tested, kImage, {}).empty());
}

TEST(MotionObjects, AGroupAmongMostlyStaticKeypointsIsNoObject) {
  std::vector<TestedKeypoint> tested = static_scene(3.0f);
  // Four failing keypoints in a row inside a static surface: the static
  // keypoints between them outvote them.
  int marked = 0;
  for (TestedKeypoint& k : tested)
    if (k.pixel.y == 250 && k.pixel.x >= 110 && k.pixel.x <= 530 &&
        (int(k.pixel.x) - 110) % 120 == 0)
      k.moving = true, marked++;
  ASSERT_EQ(marked, 4);
  MotionObjectParams params;
  params.link_px = 130;  // so they do link
  EXPECT_TRUE(find_motion_objects(tested, kImage, params).empty());
}

TEST(MotionObjects, MoversAtDifferentDepthsAreTwoObjects) {
  std::vector<TestedKeypoint> tested = static_scene(5.0f);
  place_mover(tested, cv::Rect2f(100, 200, 60, 60), 1.5f);  // 3 x 3 keypoints
  place_mover(tested, cv::Rect2f(160, 200, 60, 60), 3.5f);  // adjacent in the image
  MotionObjectParams params;
  params.min_seeds = 4;
  const std::vector<MotionObject> found = find_motion_objects(tested, kImage, params);
  ASSERT_EQ(found.size(), 2u);
  EXPECT_NE(found[0].depth, found[1].depth);
}

TEST(MotionObjects, TooFewSeedsAreNoObject) {
  std::vector<TestedKeypoint> tested = static_scene(4.0f);
  place_mover(tested, cv::Rect2f(300, 300, 40, 40), 2.0f);  // 2 x 2 keypoints
  MotionObjectParams params;
  params.min_seeds = 5;
  EXPECT_TRUE(find_motion_objects(tested, kImage, params).empty());
  params.min_seeds = 4;
  EXPECT_EQ(find_motion_objects(tested, kImage, params).size(), 1u);
}

TEST(MotionObjects, AFrameWhereMuchFailsHasNoObjects) {
  // A third of the frame failing is a wrong camera motion, not a mover.
  std::vector<TestedKeypoint> tested = static_scene(4.0f);
  place_mover(tested, cv::Rect2f(0, 0, 640, 160), 2.0f);
  EXPECT_TRUE(find_motion_objects(tested, kImage, {}).empty());
  MotionObjectParams params;
  params.max_frame_moving_share = 0.5f;
  EXPECT_EQ(find_motion_objects(tested, kImage, params).size(), 1u);
}

}  // namespace
}  // namespace depot::slam
