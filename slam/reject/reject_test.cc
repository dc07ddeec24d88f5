// The rejection rules on synthetic data: point sets with the overlap rule,
// the flow test on camera motion plus a moving patch, and the filter modes.
#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "common/error.h"
#include "slam/detect/detection.h"
#include "slam/reject/apriori_classes.h"
#include "slam/reject/flow_test.h"
#include "slam/reject/optical_flow.h"
#include "slam/reject/point_sets.h"
#include "slam/reject/rejection_filter.h"

namespace depot::slam {
namespace {

AprioriClasses table() {
  return AprioriClasses({"person", "dog"}, {"chair", "monitor_stand"});
}

Detection det(const std::string& cls, float x, float y, float w, float h) {
  Detection d;
  d.class_name = cls;
  d.confidence = 0.9f;
  d.box = cv::Rect2f(x, y, w, h);
  return d;
}

cv::KeyPoint kp(float x, float y) {
  return cv::KeyPoint(x, y, 31.0f);
}

TEST(PointSets, FollowTheOverlapRule) {
  const std::vector<Detection> dets = {det("person", 100, 100, 100, 200),
                                       det("tv", 150, 120, 100, 60),
                                       det("chair", 400, 300, 80, 80)};
  const std::vector<cv::KeyPoint> kps = {kp(110, 250),  // person only -> Z
                                         kp(160, 130),  // person and tv overlap -> Q (flow decides)
                                         kp(220, 130),  // tv only (static class) -> P
                                         kp(420, 320),  // chair -> Q
                                         kp(10, 10)};   // nothing -> P
  auto sets = assign_point_sets(kps, dets, table());
  EXPECT_EQ(sets[0], PointSet::kZ);
  EXPECT_EQ(sets[1], PointSet::kQ);
  EXPECT_EQ(sets[2], PointSet::kP);
  EXPECT_EQ(sets[3], PointSet::kQ);
  EXPECT_EQ(sets[4], PointSet::kP);
  auto inside = inside_dynamic_boxes(kps, dets, table());
  EXPECT_EQ(inside, (std::vector<bool>{true, true, false, false, false}));
}

TEST(PointSets, DepthSplitSendsBackgroundToP) {
  const std::vector<Detection> dets = {det("person", 100, 100, 100, 200),
                                       det("chair", 400, 300, 80, 80)};
  std::vector<cv::KeyPoint> kps;
  std::vector<float> depth;
  for (int k = 0; k < 6; ++k) {  // the person, 2 m away
    kps.push_back(kp(120 + 10 * k, 150));
    depth.push_back(2.0f + 0.05f * k);
  }
  kps.push_back(kp(120, 280));  // the wall 1.5 m behind the person -> P
  depth.push_back(3.5f);
  kps.push_back(kp(130, 280));  // within the margin (an arm) -> Z
  depth.push_back(2.3f);
  kps.push_back(kp(140, 280));  // no depth in the person's box -> P
  depth.push_back(0.0f);
  for (int k = 0; k < 5; ++k) {  // the chair
    kps.push_back(kp(410 + 10 * k, 320));
    depth.push_back(1.5f);
  }
  kps.push_back(kp(410, 370));  // no depth in the chair's box -> P
  depth.push_back(0.0f);
  kps.push_back(kp(420, 370));  // behind the chair: still Q (only Z is split by depth)
  depth.push_back(4.0f);
  auto sets = assign_point_sets(kps, dets, table());
  split_boxes_by_depth(kps, depth, dets, table(), 0.4f, sets);
  for (int k = 0; k < 6; ++k) EXPECT_EQ(sets[k], PointSet::kZ) << k;
  EXPECT_EQ(sets[6], PointSet::kP);
  EXPECT_EQ(sets[7], PointSet::kZ);
  EXPECT_EQ(sets[8], PointSet::kP);
  for (int k = 9; k < 14; ++k) EXPECT_EQ(sets[k], PointSet::kQ) << k;
  EXPECT_EQ(sets[14], PointSet::kP);
  EXPECT_EQ(sets[15], PointSet::kQ);

  // A box whose object has (almost) no depth decides nothing.
  std::vector<float> none(kps.size(), 0.0f);
  auto unchanged = assign_point_sets(kps, dets, table());
  split_boxes_by_depth(kps, none, dets, table(), 0.4f, unchanged);
  EXPECT_EQ(unchanged, assign_point_sets(kps, dets, table()));
}

TEST(BoxConversion, PaperEquation8) {
  // X, Y, W, H normalised centre format on a 640 x 480 image.
  cv::Rect2f b = yolo_to_pixels(0.5f, 0.25f, 0.2f, 0.1f, 640, 480);
  EXPECT_FLOAT_EQ(b.x, 256.0f);  // (0.5 - 0.1) * 640
  EXPECT_FLOAT_EQ(b.y, 96.0f);   // (0.25 - 0.05) * 480, top-left has the smaller y
  EXPECT_FLOAT_EQ(b.width, 128.0f);
  EXPECT_FLOAT_EQ(b.height, 48.0f);
}

TEST(FlowTest, MeanAndThresholdWithFloor) {
  std::vector<cv::Point2f> flow = {{3, 4}, {3, 4}, {100, 0}};
  std::vector<uint8_t> ok = {1, 1, 0};
  FlowTestResult t = mean_static_flow(flow, ok, {});
  EXPECT_FLOAT_EQ(t.mean.x, 3);
  EXPECT_FLOAT_EQ(t.mean.y, 4);
  EXPECT_FLOAT_EQ(t.z, 10);  // 2 x |(3, 4)|
  EXPECT_FALSE(flow_is_dynamic({5, 8}, t));
  EXPECT_TRUE(flow_is_dynamic({15, 4}, t));
  // A still camera gets the floor, not z = 0.
  FlowTestResult still = mean_static_flow({{0, 0}}, {1}, {});
  EXPECT_FLOAT_EQ(still.z, FlowTestParams{}.z_floor);
}

// A textured image, shifted by the camera, with a patch moving on its own.
cv::Mat textured(int seed) {
  cv::Mat img(240, 320, CV_8UC1);
  cv::RNG rng(seed);
  rng.fill(img, cv::RNG::UNIFORM, 0, 255);
  cv::GaussianBlur(img, img, cv::Size(5, 5), 1.5);
  return img;
}

// `background` shifted by the camera (cam_dx px), with `patch` pasted at
// (patch_x, patch_y): a frame of a camera moving past a moving object.
cv::Mat moved_frame(const cv::Mat& background, const cv::Mat& patch, float cam_dx, int patch_x,
                    int patch_y) {
  cv::Mat shifted;
  cv::Mat m = (cv::Mat_<double>(2, 3) << 1, 0, cam_dx, 0, 1, 0);
  cv::warpAffine(background, shifted, m, background.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
  patch.copyTo(shifted(cv::Rect(patch_x, patch_y, patch.cols, patch.rows)));
  return shifted;
}

TEST(FlowTest, SyntheticCameraMotionPlusMovingPatch) {
  cv::Mat background = textured(1), patch = textured(2)(cv::Rect(0, 0, 60, 60)).clone();
  auto frame = [&](float cam_dx, int patch_x) {
    return moved_frame(background, patch, cam_dx, patch_x, 90);
  };
  SparseFlow flow;
  flow.next_frame(frame(0, 100));
  flow.next_frame(frame(3, 115));  // camera: +3 px, patch: +15 px
  std::vector<cv::Point2f> static_pts, patch_pts;
  for (int y = 20; y < 220; y += 20)
    for (int x = 20; x < 300; x += 20) {
      if (x > 105 && x < 185 && y > 85 && y < 155) continue;
      static_pts.emplace_back(x, y);
    }
  // Interior patch points (the LK window stays on the patch).
  for (int y = 105; y <= 135; y += 10)
    for (int x = 130; x <= 160; x += 10) patch_pts.emplace_back(x, y);
  std::vector<cv::Point2f> fs, fp;
  std::vector<uint8_t> oks, okp;
  flow.flow(static_pts, fs, oks);
  flow.flow(patch_pts, fp, okp);
  FlowTestResult t = mean_static_flow(fs, oks, {});
  EXPECT_NEAR(t.mean.x, 3.0, 0.3);
  EXPECT_NEAR(t.mean.y, 0.0, 0.3);
  int static_dynamic = 0, patch_dynamic = 0, patch_tracked = 0;
  for (size_t i = 0; i < fs.size(); ++i) static_dynamic += oks[i] && flow_is_dynamic(fs[i], t);
  for (size_t i = 0; i < fp.size(); ++i) {
    patch_tracked += okp[i];
    patch_dynamic += okp[i] && flow_is_dynamic(fp[i], t);
  }
  EXPECT_LT(static_dynamic, 0.02 * fs.size());
  EXPECT_GT(patch_tracked, 0.75 * fp.size());
  EXPECT_EQ(patch_dynamic, patch_tracked);
}

// follow(): points of the previous frame found in the current one, the
// patch's where the patch went and the background's where the camera took it.
TEST(SparseFlowFollow, FindsPreviousPointsWhereTheyMoved) {
  // A patch as large as a person near the camera (120 px): LK's coarsest
  // level (1/8) still sees it whole.
  cv::Mat background = textured(1), patch = textured(2)(cv::Rect(0, 0, 120, 120)).clone();
  auto frame = [&](float cam_dx, int patch_x) {
    return moved_frame(background, patch, cam_dx, patch_x, 60);
  };
  SparseFlow flow;
  std::vector<cv::Point2f> now;
  std::vector<uint8_t> ok;
  flow.follow({{50, 50}}, now, ok);
  EXPECT_EQ(ok, std::vector<uint8_t>{0}) << "no previous frame";
  flow.next_frame(frame(0, 90));
  flow.next_frame(frame(-4, 108));  // camera: -4 px, patch: +18 px
  const std::vector<cv::Point2f> before = {{140, 110}, {160, 130}, {30, 30}, {290, 210}};
  flow.follow(before, now, ok);
  ASSERT_EQ(now.size(), before.size());
  for (size_t i = 0; i < before.size(); ++i) {
    ASSERT_TRUE(ok[i]) << i;
    EXPECT_NEAR(now[i].x - before[i].x, i < 2 ? 18.0 : -4.0, 0.5) << i;
    EXPECT_NEAR(now[i].y, before[i].y, 0.5) << i;
  }
}

TEST(AprioriClasses, RejectsUnknownClassesAndContradictions) {
  AprioriClasses t = table();
  EXPECT_EQ(t.classify("person"), MotionClass::kDynamic);
  EXPECT_EQ(t.classify("chair"), MotionClass::kPotentiallyDynamic);
  EXPECT_EQ(t.classify("rack"), MotionClass::kStatic);
  EXPECT_THROW(t.check_against({"person", "dog", "chair"}, "table.yaml", "sim"), Error);
  EXPECT_NO_THROW(
      t.check_against({"person", "dog", "chair", "monitor_stand", "tv"}, "table.yaml", "sim"));
  EXPECT_THROW(parse_rejection_mode("orb+magic"), Error);
}

}  // namespace
}  // namespace depot::slam
