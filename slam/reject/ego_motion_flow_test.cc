// The ego-motion flow test on synthetic flows: a camera motion seen by
// static points at many depths, plus a patch that moves on its own.
#include "slam/reject/ego_motion_flow.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <opencv2/calib3d.hpp>

#include "slam/camera/lens_distortion.h"
#include "slam/reject/flow_test.h"

namespace depot::slam {
namespace {

struct Scene {
  std::vector<cv::Point2f> pixels, flow;
  std::vector<float> depth;
  std::vector<uint8_t> ok, moving;
};

// Camera moves by (R, t) from previous to current; static points at 1-4 m
// give the flow of that motion (plus 0.2 px LK noise), points of a patch
// also move 5 cm sideways in the world between the frames. Pixels are the
// image's, through the camera's lens when it has one. `turn` scales the
// rotation (1 = 0.7 deg, a slow pan).
Scene make_scene(const PinholeCamera& cam, double turn = 1.0) {
  Scene s;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(20, 620), v(20, 460), z(1.0f, 4.0f);
  std::normal_distribution<float> noise(0.0f, 0.2f);
  const cv::Matx33d r = [turn] {
    cv::Matx33d m;
    cv::Rodrigues(turn * cv::Vec3d(0.004, -0.012, 0.002), m);
    return m;
  }();
  const cv::Vec3d t(0.015, -0.004, 0.01);  // current camera -> previous camera
  for (int i = 0; i < 300; ++i) {
    const cv::Point2f px(u(rng), v(rng));
    const float d = z(rng);
    const bool patch = i < 40;
    const cv::Point2f ray = undistort_pixel(cam, px);
    const Eigen::Vector3d p = cam.unproject(ray.x, ray.y, d);
    cv::Vec3d world(p.x(), p.y(), p.z());
    if (patch) world += cv::Vec3d(0.05, 0, 0);  // where it was one frame ago
    const cv::Vec3d q = r * world + t;
    const cv::Point2f prev =
        distort_pixel(cam, cv::Point2f(static_cast<float>(cam.fx * q[0] / q[2] + cam.cx),
                                       static_cast<float>(cam.fy * q[1] / q[2] + cam.cy)));
    s.pixels.push_back(px);
    s.depth.push_back(d);
    s.flow.push_back(px - prev + cv::Point2f(noise(rng), noise(rng)));
    s.ok.push_back(1);
    s.moving.push_back(patch);
  }
  return s;
}

// How many static and moving points of `s` the test flags, run with
// `model_camera`'s idea of the camera.
std::pair<int, int> flagged_points(const Scene& s, const PinholeCamera& model_camera) {
  const EgoMotionModel model = fit_ego_motion(model_camera, s.pixels, s.depth, s.flow, s.ok, {});
  EXPECT_TRUE(model.valid);
  EXPECT_GE(model.inliers, 150);
  int static_flagged = 0, moving_flagged = 0;
  for (size_t i = 0; i < s.pixels.size(); ++i) {
    cv::Point2f near, far;
    EXPECT_TRUE(
        predict_static_previous(model, model_camera, s.pixels[i], s.depth[i], 4.0f, &near, &far));
    const float r = distance_to_prediction(s.pixels[i] - s.flow[i], near, far);
    const bool flagged = r > scaled_px(EgoMotionParams().threshold_px, model_camera);
    (s.moving[i] ? moving_flagged : static_flagged) += flagged;
  }
  return {static_flagged, moving_flagged};
}

TEST(EgoMotionFlow, SeparatesAMovingPatchFromStaticPointsAtAllDepths) {
  const PinholeCamera cam;
  const Scene s = make_scene(cam);
  const EgoMotionModel model = fit_ego_motion(cam, s.pixels, s.depth, s.flow, s.ok, {});
  ASSERT_TRUE(model.valid);
  EXPECT_GE(model.inliers, 250);
  const auto [static_flagged, moving_flagged] = flagged_points(s, cam);
  EXPECT_EQ(static_flagged, 0);
  EXPECT_GE(moving_flagged, 38);  // of 40 (5 cm at up to 4 m is at least 6 px)

  // The paper's mean-flow test on the same flows: parallax and rotation make
  // static flow vary across the image, so it cannot draw this line as well.
  const FlowTestResult mean = mean_static_flow(s.flow, s.ok, {});
  int mean_static_flagged = 0, mean_moving_flagged = 0;
  for (size_t i = 0; i < s.pixels.size(); ++i)
    (s.moving[i] ? mean_moving_flagged : mean_static_flagged) += flow_is_dynamic(s.flow[i], mean);
  const int ego_errors = static_flagged + (40 - moving_flagged);
  const int mean_errors = mean_static_flagged + (40 - mean_moving_flagged);
  EXPECT_GT(mean_errors, ego_errors + 10);
}

// Through a Kinect-like barrel lens the test still separates the patch when
// it knows the lens; read as a pinhole, the same flows flag static points.
TEST(EgoMotionFlow, ALensIsUndoneBeforeTheMotionIsFitted) {
  PinholeCamera lensed;
  lensed.lens = {-0.25, 0.08, 0.0015, -0.001, 0.0};
  set_undistorted_bounds(lensed, "test");
  const Scene s = make_scene(lensed, 3.0);  // 2.1 deg: turning at 63 deg/s
  const auto [static_flagged, moving_flagged] = flagged_points(s, lensed);
  EXPECT_EQ(static_flagged, 0);
  EXPECT_GE(moving_flagged, 38);
  const auto [static_as_pinhole, moving_as_pinhole] = flagged_points(s, PinholeCamera());
  EXPECT_GT(static_as_pinhole + (40 - moving_as_pinhole), 10);
}

TEST(EgoMotionFlow, NeedsEnoughPointsWithDepth) {
  const PinholeCamera cam;
  Scene s = make_scene(cam);
  for (size_t i = 8; i < s.depth.size(); ++i) s.depth[i] = 0;  // no depth
  const EgoMotionModel model = fit_ego_motion(cam, s.pixels, s.depth, s.flow, s.ok, {});
  EXPECT_FALSE(model.valid);
  cv::Point2f near, far;
  EXPECT_FALSE(predict_static_previous(model, cam, s.pixels[0], 2.0f, 4.0f, &near, &far));
}

TEST(EgoMotionFlow, PointsWithoutDepthAreTestedFromTheSensorRangeToInfinity) {
  const PinholeCamera cam;
  const Scene s = make_scene(cam);
  const EgoMotionModel model = fit_ego_motion(cam, s.pixels, s.depth, s.flow, s.ok, {});
  ASSERT_TRUE(model.valid);
  // A static point far away (no depth): its flow lies on the predicted
  // segment; the same pixel with the moving patch's flow does not.
  const cv::Point2f pixel(320, 240);
  cv::Point2f near, far;
  ASSERT_TRUE(predict_static_previous(model, cam, pixel, 0.0f, 4.0f, &near, &far));
  EXPECT_GT(cv::norm(near - far), 0.5);  // translation shifts near points more
  const cv::Point2f at_10m = near + 0.6f * (far - near);
  EXPECT_LT(distance_to_prediction(at_10m, near, far), 0.01f);
  EXPECT_GT(distance_to_prediction(near + cv::Point2f(0, 8), near, far), 5.0f);
}

}  // namespace
}  // namespace depot::slam
