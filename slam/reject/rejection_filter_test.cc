// The masked mode's still-object test on synthetic frames: a person box over
// a near textured patch (1.5 m) before a textured wall (3 m); the camera pans
// 3 px between two frames. A person that pans with the wall keeps the
// keypoints whose flow agrees with the wall's; one that moves on its own
// loses every keypoint on it, even those whose own flow would pass.
#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "slam/detect/detection_file.h"
#include "slam/reject/rejection_filter.h"

namespace depot::slam {
namespace {

constexpr int kWidth = 320, kHeight = 240;
const cv::Rect kPerson(120, 60, 60, 110);

cv::Mat textured(int seed, cv::Size size) {
  cv::Mat img(size, CV_8UC1);
  cv::RNG rng(seed);
  rng.fill(img, cv::RNG::UNIFORM, 0, 255);
  cv::GaussianBlur(img, img, cv::Size(5, 5), 1.5);
  return img;
}

struct SyntheticFrame {
  cv::Mat gray, bgr, depth;
  cv::Rect person;
};

// The wall panned by `pan` px, the person drawn at kPerson moved by
// `person_dx` px.
SyntheticFrame make_frame(float pan, int person_dx) {
  static const cv::Mat wall = textured(1, {kWidth, kHeight});
  static const cv::Mat skin = textured(2, kPerson.size());
  SyntheticFrame f;
  const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, pan, 0, 1, 0);
  cv::warpAffine(wall, f.gray, shift, wall.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
  f.person = kPerson + cv::Point(person_dx, 0);
  skin.copyTo(f.gray(f.person));
  cv::cvtColor(f.gray, f.bgr, cv::COLOR_GRAY2BGR);
  f.depth = cv::Mat(f.gray.size(), CV_32F, cv::Scalar(3.0f));
  f.depth(f.person).setTo(1.5f);
  return f;
}

std::vector<cv::KeyPoint> grid_keypoints() {
  std::vector<cv::KeyPoint> kps;
  for (int y = 20; y < kHeight - 20; y += 10)
    for (int x = 20; x < kWidth - 20; x += 10) kps.emplace_back(float(x), float(y), 31.0f);
  return kps;
}

struct Decisions {
  int inside = 0, inside_kept = 0;        // well inside the person (LK window on it)
  int on_person = 0, on_person_kept = 0;  // anywhere on the person, edges too
  int wall = 0, wall_kept = 0, still_objects = 0;
};

// Two frames through the masked filter; the decisions of the second for
// keypoints on the person (and well inside it, where the LK window stays on
// it) and on the wall away from it.
Decisions run_two_frames(int person_dx, float still_object_max_moving) {
  const SyntheticFrame a = make_frame(0, 0), b = make_frame(3, person_dx);
  auto frame_detections = [](double t, const cv::Rect& box) {
    Detection d;
    d.class_name = "person";
    d.confidence = 0.9f;
    d.box = cv::Rect2f(box);
    return DetectionFrame{t, {d}};
  };
  FileDetector detector({frame_detections(1.0, a.person), frame_detections(2.0, b.person)});
  RejectionParams params;
  params.still_object_max_moving = still_object_max_moving;
  RejectionFilter filter(RejectionMode::kMasked, AprioriClasses({"person"}, {"chair"}), &detector,
                         params);
  const std::vector<cv::KeyPoint> kps = grid_keypoints();
  std::vector<uint8_t> keep;
  Decisions d;
  for (const SyntheticFrame* f : {&a, &b}) {
    const double t = f == &a ? 1.0 : 2.0;
    const FrameImages images{f->bgr, f->gray, f->depth, t, f == &a ? 0 : 1};
    filter.begin_frame(images);
    filter.filter(images, kps, keep);
  }
  d.still_objects = filter.last_stats().still_objects;
  const cv::Rect inner(b.person.x + 12, b.person.y + 12, b.person.width - 24, b.person.height - 24);
  cv::Rect near_person(b.person.x - 30, b.person.y - 30, b.person.width + 60, b.person.height + 60);
  for (size_t i = 0; i < kps.size(); ++i) {
    const cv::Point p(kps[i].pt);
    if (b.person.contains(p)) {
      d.on_person++;
      d.on_person_kept += keep[i];
    }
    if (inner.contains(p)) {
      d.inside++;
      d.inside_kept += keep[i];
    } else if (!near_person.contains(p)) {
      d.wall++;
      d.wall_kept += keep[i];
    }
  }
  return d;
}

TEST(RejectionFilter, AStillPersonKeepsThePointsThatMoveWithTheScene) {
  const Decisions d = run_two_frames(3, RejectionParams{}.still_object_max_moving);
  ASSERT_GT(d.inside, 20);
  EXPECT_EQ(d.still_objects, 1);
  EXPECT_GT(d.inside_kept, 0.8 * d.inside);
  EXPECT_GT(d.wall_kept, 0.95 * d.wall);
}

TEST(RejectionFilter, AMovingPersonLosesEveryPointOnIt) {
  const Decisions d = run_two_frames(15, RejectionParams{}.still_object_max_moving);
  ASSERT_GT(d.inside, 20);
  EXPECT_EQ(d.still_objects, 0);
  EXPECT_EQ(d.on_person_kept, 0);
  EXPECT_GT(d.wall_kept, 0.95 * d.wall);
}

TEST(RejectionFilter, WithoutTheStillTestAPersonIsRejectedWhole) {
  const Decisions d = run_two_frames(3, 0.0f);
  ASSERT_GT(d.inside, 20);
  EXPECT_EQ(d.still_objects, 0);
  EXPECT_EQ(d.on_person_kept, 0);
}

}  // namespace
}  // namespace depot::slam
