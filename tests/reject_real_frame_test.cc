// The paper's claim on a real TUM fr3/walking_xyz frame: Yolo-Fastest finds
// both people, and `full` rejects the keypoints on them while keeping those
// on the monitors and the desk.
#include <filesystem>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "slam/detect/detector_config.h"
#include "slam/detect/detector_factory.h"
#include "slam/feature/orb_extractor.h"
#include "slam/reject/rejection_filter.h"

namespace fs = std::filesystem;

namespace depot::slam {
namespace {

const std::string kFrame = std::string(DEPOT_SHARED_DATA) + "/tum/fr3_walking_xyz_frame";

bool inside(const cv::Rect2f& b, const cv::Point2f& p) {
  return b.contains(p);
}

TEST(RejectRealFrame, FullModeRejectsPeopleKeepsMonitorsAndDesk) {
  if (!fs::exists(kFrame)) GTEST_SKIP() << "shared data missing: " << kFrame;
  cv::Mat bgr, depth16;
  for (const auto& e : fs::directory_iterator(kFrame + "/rgb")) bgr = cv::imread(e.path().string());
  for (const auto& e : fs::directory_iterator(kFrame + "/depth"))
    depth16 = cv::imread(e.path().string(), -1);
  cv::Mat gray, depth;
  cv::cvtColor(bgr, gray, cv::COLOR_BGR2GRAY);
  depth16.convertTo(depth, CV_32F, 1.0 / 5000);

  auto detector = make_dnn_detector(
      load_detector_config(std::string(DEPOT_SOURCE_DIR) + "/scenes/detectors/yolo_fastest.yaml"));
  AprioriClasses classes =
      AprioriClasses::load(std::string(DEPOT_SOURCE_DIR) + "/scenes/apriori/coco.yaml");
  classes.check_against(detector->class_names(), "coco.yaml", detector->name());
  RejectionFilter filter(RejectionMode::kFull, classes, detector.get());

  OrbExtractor extractor(OrbParams{});
  std::vector<cv::KeyPoint> kps;
  cv::Mat desc;
  const FrameImages images{bgr, gray, depth, 0.0, 0};
  filter.begin_frame(images);
  extractor.extract(gray, cv::Mat(), kps, desc);
  std::vector<uint8_t> keep(kps.size(), 1);
  filter.filter(images, kps, keep);

  std::vector<cv::Rect2f> people, monitors, others;
  for (const auto& d : filter.last_detections()) {
    if (d.class_name == "person")
      people.push_back(d.box);
    else if (d.class_name == "tvmonitor" || d.class_name == "laptop")
      monitors.push_back(d.box);
    else
      others.push_back(d.box);
  }
  ASSERT_EQ(people.size(), 2u) << "both people must be found";
  int on_people = 0, on_people_rejected = 0, on_monitors = 0, on_monitors_kept = 0, elsewhere = 0,
      elsewhere_kept = 0;
  for (size_t i = 0; i < kps.size(); ++i) {
    const bool in_person = inside(people[0], kps[i].pt) || inside(people[1], kps[i].pt);
    bool in_monitor = false, in_other = false;
    for (const auto& m : monitors) in_monitor = in_monitor || inside(m, kps[i].pt);
    for (const auto& o : others) in_other = in_other || inside(o, kps[i].pt);
    if (in_person && in_other && !in_monitor)
      continue;  // e.g. person on a chair: the flow test decides (Q)
    if (in_person && !in_monitor) {
      ++on_people;
      on_people_rejected += !keep[i];
    } else if (in_monitor) {
      ++on_monitors;
      on_monitors_kept += keep[i];
    } else {
      ++elsewhere;
      elsewhere_kept += keep[i];
    }
  }
  EXPECT_GT(on_people, 50);
  EXPECT_EQ(on_people_rejected, on_people) << "every keypoint only in a person box (Z) is rejected";
  EXPECT_EQ(elsewhere_kept, elsewhere) << "the desk and the rest of the room are kept";
  if (!monitors.empty()) {
    EXPECT_GT(on_monitors, 0);
    EXPECT_EQ(on_monitors_kept, on_monitors)
        << "monitor keypoints overlapping a person are not thrown away";
  }
  std::printf(
      "people %d (rejected %d), monitors %d (kept %d), elsewhere %d (kept %d), detections %zu\n",
      on_people, on_people_rejected, on_monitors, on_monitors_kept, elsewhere, elsewhere_kept,
      filter.last_detections().size());
  for (const auto& d : filter.last_detections())
    std::printf("  %s %.2f [%.0f %.0f %.0f %.0f]\n", d.class_name.c_str(), d.confidence, d.box.x,
                d.box.y, d.box.width, d.box.height);
}

}  // namespace
}  // namespace depot::slam
