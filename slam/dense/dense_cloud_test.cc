#include "slam/dense/dense_cloud.h"

#include <gtest/gtest.h>

#include "common/error.h"

namespace depot::slam {
namespace {

PinholeCamera small_camera() {
  PinholeCamera camera;
  camera.width = 80;
  camera.height = 60;
  camera.fx = camera.fy = 64;  // pixels 1/32 m apart on a wall 2 m away: exact in binary
  camera.cx = 40;
  camera.cy = 30;
  return camera;
}

// A camera at x = `x` (world = camera axes otherwise) looking at a wall at
// world z = 2, with a box 1 m in front of it over the pixels `box`.
struct View {
  Pose T_wc = Pose::Identity();
  cv::Mat depth, bgr, moving;
};
View wall_view(const PinholeCamera& camera, double x, cv::Rect box = {}) {
  View view;
  view.T_wc.translation() = Eigen::Vector3d(x, 0, 0);
  view.depth = cv::Mat(camera.height, camera.width, CV_32F, cv::Scalar(2.0f));
  view.bgr = cv::Mat(camera.height, camera.width, CV_8UC3, cv::Scalar(10, 20, 30));
  view.moving = cv::Mat::zeros(camera.height, camera.width, CV_8U);
  if (!box.empty()) {
    view.depth(box).setTo(1.0f);
    view.bgr(box).setTo(cv::Scalar(200, 200, 200));
    view.moving(box).setTo(255);
  }
  return view;
}

TEST(DenseCloud, AWallSeenTwiceIsOneLayerOfVoxelsOnIt) {
  const PinholeCamera camera = small_camera();
  DenseCloudParams params;
  params.stride = 1;
  params.min_views = 1;
  DenseCloud cloud(camera, params);
  // b moved 8 pixels' worth (0.25 m) to the right.
  const View a = wall_view(camera, 0.0), b = wall_view(camera, 0.25);
  cloud.add_view(a.T_wc, a.depth, a.bgr);
  cloud.add_view(b.T_wc, b.depth, b.bgr);
  const std::vector<PlyPoint> points = cloud.points();
  // Samples lie 3.1 cm apart, so each is a voxel of its own: 80 + 8 columns
  // of 60 rows, one layer at z = 2.
  ASSERT_EQ(points.size(), 88u * 60u);
  int both = 0;
  for (const PlyPoint& p : points) {
    EXPECT_NEAR(p.position.z(), 2.0f, 1e-5f);
    EXPECT_EQ(p.bgr, cv::Vec3b(10, 20, 30));
    both += p.count == 2;
    // Both views see x in [-1.0, 1.22]: there every voxel counts both.
    const bool seen_by_both = p.position.x() >= -1.0f && p.position.x() <= 1.22f;
    EXPECT_EQ(p.count, seen_by_both ? 2 : 1) << p.position.x();
  }
  EXPECT_EQ(both, 72 * 60);
  EXPECT_EQ(cloud.views(), 2);
}

TEST(DenseCloud, MovingPixelsAndTheirOutlineAreLeftOut) {
  const PinholeCamera camera = small_camera();
  DenseCloudParams params;
  params.stride = 1;
  params.mask_margin_px = 2;
  params.min_views = 1;
  const cv::Rect box(30, 20, 12, 16);
  const View view = wall_view(camera, 0.0, box);
  DenseCloud masked(camera, params), unmasked(camera, params);
  masked.add_view(view.T_wc, view.depth, view.bgr, view.moving);
  unmasked.add_view(view.T_wc, view.depth, view.bgr);
  auto on_box = [](const std::vector<PlyPoint>& points) {
    int n = 0;
    for (const PlyPoint& p : points) n += p.position.z() < 1.5f;
    return n;
  };
  EXPECT_GT(on_box(unmasked.points()), 20);
  EXPECT_EQ(on_box(masked.points()), 0);
  // The margin: no wall pixel within 2 px of the box's sides either (the
  // grown mask is a disc-dilation, so corners are rounder).
  const std::vector<PlyPoint> wall = masked.points();
  for (const PlyPoint& p : wall) {
    const double u = camera.fx * p.position.x() / p.position.z() + camera.cx;
    const double v = camera.fy * p.position.y() / p.position.z() + camera.cy;
    const bool beside = u > box.x - 2.5 && u < box.x + box.width + 1.5 && v > box.y - 0.5 &&
                        v < box.y + box.height - 0.5;
    const bool above_or_below = v > box.y - 2.5 && v < box.y + box.height + 1.5 &&
                                u > box.x - 0.5 && u < box.x + box.width - 0.5;
    EXPECT_FALSE(beside || above_or_below) << u << " " << v;
  }
  EXPECT_EQ(wall.size(), 80u * 60u - (12u + 4u) * 16u - 12u * 4u - 4u * 4u + 4u * 2u)
      << "the box and a 2-px disc margin around it";
}

TEST(DenseCloud, MinimumViewsDropsWhatOnlyOneKeyframeSaw) {
  const PinholeCamera camera = small_camera();
  DenseCloudParams params;
  params.stride = 1;
  params.free_space = false;  // min_views alone
  DenseCloud cloud(camera, params);
  // A box in front of the wall in the first view only: a thing that moved away.
  const View a = wall_view(camera, 0.0, cv::Rect(30, 20, 12, 16)), b = wall_view(camera, 0.0);
  cloud.add_view(a.T_wc, a.depth, a.bgr);
  cloud.add_view(b.T_wc, b.depth, b.bgr);
  for (const PlyPoint& p : cloud.points()) {
    EXPECT_GT(p.position.z(), 1.5f);
    EXPECT_EQ(p.count, 2);
  }
}

// Something that stood in front of the wall in two keyframes and was gone
// in three: those see the wall through it, so it is left out; without free
// space it stays (seen twice).
TEST(DenseCloud, FreeSpaceLeavesOutWhatOtherKeyframesSeeThrough) {
  const PinholeCamera camera = small_camera();
  DenseCloudParams params;
  params.stride = 1;
  const cv::Rect box(30, 20, 12, 16);
  const View there = wall_view(camera, 0.0, box), gone = wall_view(camera, 0.0);
  auto boxed_points = [&](bool free_space) {
    params.free_space = free_space;
    DenseCloud cloud(camera, params);
    for (int k = 0; k < 2; ++k) cloud.add_view(there.T_wc, there.depth, there.bgr);
    for (int k = 0; k < 3; ++k) cloud.add_view(gone.T_wc, gone.depth, gone.bgr);
    int n = 0, wall = 0;
    for (const PlyPoint& p : cloud.points()) (p.position.z() < 1.5f ? n : wall)++;
    EXPECT_EQ(wall, 80 * 60) << "the wall behind is seen standing by three of five";
    return n;
  };
  EXPECT_EQ(boxed_points(true), 0);
  EXPECT_GT(boxed_points(false), 50);  // 12 x 16 px at 1.6 cm a pixel: 108 voxels
}

// A keyframe whose mask marks a voxel as moving votes against it: a mover
// its mask caught in one keyframe and missed in another is left out.
TEST(DenseCloud, AMaskedSightingVotesAgainstAVoxel) {
  const PinholeCamera camera = small_camera();
  DenseCloudParams params;
  params.stride = 1;
  params.min_views = 1;
  const cv::Rect box(30, 20, 12, 16);
  const View view = wall_view(camera, 0.0, box);
  DenseCloud cloud(camera, params);
  cloud.add_view(view.T_wc, view.depth, view.bgr);               // missed
  cloud.add_view(view.T_wc, view.depth, view.bgr, view.moving);  // caught
  for (const PlyPoint& p : cloud.points()) EXPECT_GT(p.position.z(), 1.5f);
  DenseCloud unmasked(camera, params);
  for (int k = 0; k < 2; ++k) unmasked.add_view(view.T_wc, view.depth, view.bgr);
  int boxed = 0;
  for (const PlyPoint& p : unmasked.points()) boxed += p.position.z() < 1.5f;
  EXPECT_GT(boxed, 50);
}

TEST(DenseCloud, FarDepthAndNoDepthAreLeftOut) {
  const PinholeCamera camera = small_camera();
  DenseCloudParams params;
  params.max_depth_m = 1.5f;
  params.min_views = 1;
  DenseCloud cloud(camera, params);
  const View view = wall_view(camera, 0.0, cv::Rect(30, 20, 12, 16));
  cv::Mat depth = view.depth.clone();
  depth(cv::Rect(0, 0, 10, 10)).setTo(0.0f);
  cloud.add_view(view.T_wc, depth, view.bgr);
  const std::vector<PlyPoint> points = cloud.points();
  ASSERT_FALSE(points.empty());
  for (const PlyPoint& p : points) EXPECT_NEAR(p.position.z(), 1.0f, 1e-5f);  // the box only
}

TEST(DenseCloud, SameViewsGiveTheSamePoints) {
  const PinholeCamera camera = small_camera();
  const View a = wall_view(camera, 0.0, cv::Rect(5, 5, 20, 20)), b = wall_view(camera, 0.17);
  auto fuse = [&] {
    DenseCloud cloud(camera);
    cloud.add_view(a.T_wc, a.depth, a.bgr);
    cloud.add_view(b.T_wc, b.depth, b.bgr);
    return cloud.points();
  };
  const std::vector<PlyPoint> first = fuse(), second = fuse();
  ASSERT_EQ(first.size(), second.size());
  for (size_t i = 0; i < first.size(); ++i) {
    EXPECT_EQ(first[i].position, second[i].position);
    EXPECT_EQ(first[i].count, second[i].count);
  }
}

TEST(DenseCloud, BadParametersAndImagesAreOneError) {
  const PinholeCamera camera = small_camera();
  DenseCloudParams bad;
  bad.voxel_m = 0;
  EXPECT_THROW(DenseCloud(camera, bad), Error);
  bad = {};
  bad.max_depth_m = std::nanf("");
  EXPECT_THROW(DenseCloud(camera, bad), Error);
  bad = {};
  bad.min_views = 0;
  EXPECT_THROW(DenseCloud(camera, bad), Error);
  DenseCloud cloud(camera);
  const View view = wall_view(camera, 0.0);
  cv::Mat small_depth(10, 10, CV_32F, cv::Scalar(1.0f));
  EXPECT_THROW(cloud.add_view(view.T_wc, small_depth, view.bgr), Error);
}

}  // namespace
}  // namespace depot::slam
