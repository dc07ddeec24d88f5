// Labels of written datasets: instance masks agree with depth and object
// poses, moving flags agree with the motion, boxes are the masks' bounds,
// and pushed chairs really move.
#include <cmath>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "dataset/boxes.h"
#include "dataset/dataset_files.h"
#include "tests/support/dataset_reader.h"
#include "tests/support/render_helpers.h"

namespace depot::test {
namespace {

// Fraction of an instance's labelled pixels whose back-projected 3-D point
// lies inside the instance's extent (inflated by `margin`) at its pose.
double fraction_inside(const Dataset& d, size_t frame, int id, const Pose& pose, double margin,
                       int* count) {
  const Calibration& c = d.calibration;
  cv::Mat depth = d.depth_metres(frame), labels = d.labels_image(frame);
  Eigen::AlignedBox3d box = d.objects.at(id).extent;
  box.min().array() -= margin;
  box.max().array() += margin;
  const Pose object_from_camera = pose.inverse() * d.groundtruth[frame].pose;
  int inside = 0, total = 0;
  for (int v = 0; v < depth.rows; ++v)
    for (int u = 0; u < depth.cols; ++u) {
      if (labels.at<uint16_t>(v, u) != id) continue;
      const double z = depth.at<float>(v, u);
      if (z <= 0) continue;
      Eigen::Vector3d p =
          object_from_camera * Eigen::Vector3d((u - c.cx) * z / c.fx, (v - c.cy) * z / c.fy, z);
      ++total;
      inside += box.contains(p);
    }
  *count = total;
  return total ? static_cast<double>(inside) / total : 0.0;
}

TEST(SimLabels, MasksLieInsideTheirObjectsAtTheirPoses) {
  std::string root = render_small({"depot_walking_xyz", 60, 320, true});
  Dataset d = read_dataset(root);
  int checked_moving = 0, checked_static = 0;
  for (size_t f = 0; f < d.frames.size(); f += 6) {
    for (const auto& [id, info] : d.objects) {
      if (info.kind == "structure") continue;
      const bool moves = info.kind == "actor" || info.kind == "pushable";
      const Pose pose = moves ? d.object_poses[f].at(id).pose : info.pose;
      int count = 0;
      double frac = fraction_inside(d, f, id, pose, 0.03, &count);
      if (count < 100) continue;
      EXPECT_GT(frac, 0.99) << info.name << " frame " << f << " (" << count << " px)";
      (moves ? checked_moving : checked_static)++;
      // A mask must not fit a wrong pose: shifted by more than its size it falls outside.
      Pose shifted = pose;
      shifted.translation() += pose.linear().col(0) * (info.extent.sizes().x() + 0.3);
      EXPECT_LT(fraction_inside(d, f, id, shifted, 0.03, &count), 0.9) << info.name;
    }
  }
  EXPECT_GE(checked_moving, 10) << "walkers and chairs must be seen and checked";
  EXPECT_GE(checked_static, 50);
}

TEST(SimLabels, MovingFlagsMatchMotionAndPushedChairMoves) {
  std::string root = render_small({"depot_walking_xyz", 100, 160, true});
  Dataset d = read_dataset(root);
  const int walker = d.object("walker_1").id, chair_a = d.object("chair_a").id,
            pushed = d.object("chair_pushed").id;
  int walker_moving = 0, pushed_moving = 0;
  for (size_t f = 0; f < d.frames.size(); ++f) {
    walker_moving += d.object_poses[f].at(walker).moving;
    EXPECT_FALSE(d.object_poses[f].at(chair_a).moving) << "frame " << f;
    EXPECT_LT(
        translation_between(d.object_poses[f].at(chair_a).pose, d.object_poses[0].at(chair_a).pose),
        0.001);
    const ObjectPose& p = d.object_poses[f].at(pushed);
    pushed_moving += p.moving;
    if (f > 0) {
      const ObjectPose& prev = d.object_poses[f - 1].at(pushed);
      const double dt = translation_between(p.pose, prev.pose);
      const double dr = rotation_angle_between(p.pose, prev.pose) * 180 / M_PI;
      // The flag is exactly "moved > 1 mm or > 0.1 deg since the previous frame".
      if (dt > 0.0011 || dr > 0.11) {
        EXPECT_TRUE(p.moving) << "frame " << f;
      }
      if (dt < 0.0009 && dr < 0.09) {
        EXPECT_FALSE(p.moving) << "frame " << f;
      }
    }
  }
  EXPECT_EQ(walker_moving, static_cast<int>(d.frames.size()));
  EXPECT_GT(pushed_moving, 20);
  const double pushed_distance = translation_between(d.object_poses.back().at(pushed).pose,
                                                     d.object_poses.front().at(pushed).pose);
  EXPECT_GT(pushed_distance, 0.5) << "the pushed chair must really travel";
  // Pushed, not knocked over: it stays upright.
  const Eigen::Vector3d up = d.object_poses.back().at(pushed).pose.linear().col(2);
  EXPECT_GT(up.z(), 0.95);
}

TEST(SimLabels, SittingPeopleMoveSlightlyInPlace) {
  std::string root = render_small({"depot_sitting_static", 40, 160, true});
  Dataset d = read_dataset(root);
  const int sitter = d.object("sitter_1").id;
  int moving = 0;
  for (size_t f = 0; f < d.frames.size(); ++f) {
    moving += d.object_poses[f].at(sitter).moving;
    EXPECT_LT(
        translation_between(d.object_poses[f].at(sitter).pose, d.object_poses[0].at(sitter).pose),
        1e-9);
  }
  EXPECT_GT(moving, 30) << "head and arms move, so the person is flagged moving";
}

TEST(SimLabels, BoxesAreTheTightBoundsOfTheMasks) {
  std::string root = render_small({"depot_walking_xyz", 20, 160, true, std::nullopt, true});
  Dataset d = read_dataset(root);
  int boxes = 0;
  std::map<std::string, size_t> frame_of;
  for (size_t i = 0; i < d.frames.size(); ++i)
    frame_of[dataset::format_timestamp(d.frames[i].rgb_timestamp)] = i;
  for (const dataset::BoxRecord& b : dataset::read_boxes(root)) {
    const std::string line = dataset::format_box(b);
    cv::Mat labels = d.labels_image(frame_of.at(dataset::format_timestamp(b.timestamp)));
    cv::Mat mask = labels == b.id;
    cv::Rect r = cv::boundingRect(mask);
    EXPECT_EQ(r, cv::Rect(b.x1, b.y1, b.x2 - b.x1, b.y2 - b.y1)) << line;
    EXPECT_EQ(cv::countNonZero(mask), b.visible_pixels) << line;
    EXPECT_EQ(d.objects.at(b.id).class_name, b.class_name);
    ++boxes;
  }
  EXPECT_GT(boxes, 20);
  // The YOLO export has one label file per image, normalised boxes in [0, 1].
  std::ifstream names(root + "/yolo/data.yaml");
  EXPECT_TRUE(names.good());
  std::ifstream yolo(root + "/yolo/labels/" + std::string(d.labels[5].path).substr(7, 17) + ".txt");
  ASSERT_TRUE(yolo.good());
  int cls;
  double cx, cy, w, h;
  int lines = 0;
  while (yolo >> cls >> cx >> cy >> w >> h) {
    ++lines;
    EXPECT_GE(cls, 0);
    for (double v : {cx, cy, w, h}) {
      EXPECT_GE(v, 0.0);
      EXPECT_LE(v, 1.0);
    }
  }
  EXPECT_GT(lines, 0);
}

}  // namespace
}  // namespace depot::test
