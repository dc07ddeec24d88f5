// The detection thread's FIFO: each frame's own detections, in order, with
// several frames queued; duplicate submissions ignored; a detector error
// rethrown by the wait for its frame only.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "common/error.h"
#include "common/testing/error_of.h"
#include "slam/detect/detection_file.h"
#include "slam/detect/detection_thread.h"
#include "slam/detect/detector_config.h"
#include "slam/detect/detector_factory.h"
#include "slam/detect/test_support.h"

namespace depot::slam {
namespace {

// Frame k (timestamp k + 1) holds k + 1 people, the first at x = 10 (k + 1).
FileDetector replay(int frames) {
  std::vector<DetectionFrame> out;
  for (int k = 0; k < frames; ++k) {
    DetectionFrame f;
    f.timestamp = k + 1.0;
    for (int j = 0; j <= k; ++j) {
      Detection d;
      d.class_name = "person";
      d.confidence = 0.9f;
      d.box = cv::Rect2f(10.0f * (k + 1) + 100.0f * j, 20, 50, 100);
      f.detections.push_back(d);
    }
    out.push_back(f);
  }
  return FileDetector(out);
}

TEST(DetectionThread, ReturnsEachFramesOwnDetectionsWithSeveralQueued) {
  FileDetector detector = replay(3);
  DetectionThread thread(detector);
  const cv::Mat image(48, 64, CV_8UC3, cv::Scalar::all(0));
  for (long k = 0; k < 3; ++k) thread.submit(image, k + 1.0, k);
  EXPECT_EQ(thread.queued(), 3u);
  for (long k = 0; k < 3; ++k) {
    double waited = -1, detect = -1;
    const std::vector<Detection> dets = thread.wait(k, &waited, &detect);
    ASSERT_EQ(dets.size(), static_cast<size_t>(k + 1)) << "frame " << k;
    EXPECT_FLOAT_EQ(dets[0].box.x, 10.0f * (k + 1)) << "frame " << k;
    EXPECT_GE(waited, 0.0);
    EXPECT_GE(detect, 0.0);
    EXPECT_EQ(thread.queued(), static_cast<size_t>(2 - k));
  }
  // A frame is forgotten once waited for; so is an earlier frame never
  // waited for.
  EXPECT_NE(error_of([&] { thread.wait(1); }, "").find("frame 1: was not submitted"),
            std::string::npos);
  thread.submit(image, 1.0, 10);
  thread.submit(image, 2.0, 11);
  EXPECT_EQ(thread.wait(11).size(), 2u);
  EXPECT_EQ(thread.queued(), 0u);
  EXPECT_THROW(thread.wait(10), Error);
}

TEST(DetectionThread, DuplicateSubmitIsANoOp) {
  FileDetector detector = replay(3);
  DetectionThread thread(detector);
  const cv::Mat image(48, 64, CV_8UC3, cv::Scalar::all(0));
  thread.submit(image, 1.0, 0);
  thread.submit(image, 2.0, 1);
  // Frame 1 again (as when a frame handed over ahead is tracked), here with
  // another timestamp: the first submission stands.
  thread.submit(image, 3.0, 1);
  thread.submit(image, 2.0, 1);
  EXPECT_EQ(thread.queued(), 2u);
  EXPECT_EQ(thread.wait(0).size(), 1u);
  EXPECT_EQ(thread.wait(1).size(), 2u);  // frame 1's, not timestamp 3's
  EXPECT_THROW(thread.wait(1), Error);   // one job, waited for once
  // Once waited for, the same index is a new job.
  thread.submit(image, 3.0, 1);
  EXPECT_EQ(thread.wait(1).size(), 3u);
}

TEST(DetectionThread, FullQueueIsAnError) {
  FileDetector detector = replay(3);
  DetectionThread thread(detector, 2);
  const cv::Mat image(48, 64, CV_8UC3, cv::Scalar::all(0));
  thread.submit(image, 1.0, 0);
  thread.submit(image, 2.0, 1);
  thread.submit(image, 2.0, 1);  // duplicate: still fine
  EXPECT_NE(error_of([&] { thread.submit(image, 3.0, 2); }, "").find("frame 2: detection queue"),
            std::string::npos);
  EXPECT_EQ(thread.wait(0).size(), 1u);
  thread.submit(image, 3.0, 2);
  EXPECT_EQ(thread.wait(2).size(), 3u);
}

// Yolo-Fastest 1.1 on the real TUM frame and its mirror image, queued
// together, with a grey (invalid) frame between them.
class DetectionThreadReal : public ::testing::Test {
 protected:
  void SetUp() override {
    DEPOT_REQUIRE_SHARED_DATA();
    frame_ = cv::imread(test::tum_frame(), cv::IMREAD_COLOR);
    ASSERT_FALSE(frame_.empty()) << test::tum_frame();
    cv::flip(frame_, mirror_, 1);
    cv::cvtColor(frame_, grey_, cv::COLOR_BGR2GRAY);
    DetectorConfig c;
    c.type = "darknet";
    c.config = test::yolo_fastest_dir() + "/yolo-fastest-1.1.cfg";
    c.model = test::yolo_fastest_dir() + "/yolo-fastest-1.1.weights";
    c.names = test::yolo_fastest_dir() + "/coco.names";
    detector_ = make_dnn_detector(c);
  }
  static void expect_same(const std::vector<Detection>& a, const std::vector<Detection>& b,
                          const char* what) {
    ASSERT_EQ(a.size(), b.size()) << what;
    for (size_t i = 0; i < a.size(); ++i) {
      EXPECT_EQ(a[i].class_name, b[i].class_name) << what;
      EXPECT_EQ(a[i].box, b[i].box) << what;
    }
  }
  cv::Mat frame_, mirror_, grey_;
  std::unique_ptr<Detector> detector_;
};

TEST_F(DetectionThreadReal, EachFramesOwnBoxesAndItsOwnError) {
  const std::vector<Detection> direct = detector_->detect(frame_, 1.0, 0);
  const std::vector<Detection> direct_mirror = detector_->detect(mirror_, 3.0, 2);
  ASSERT_FALSE(direct.empty());
  ASSERT_NE(direct[0].box, direct_mirror[0].box);
  DetectionThread thread(*detector_);
  thread.submit(frame_, 1.0, 0);
  thread.submit(grey_, 2.0, 1);
  thread.submit(mirror_, 3.0, 2);
  EXPECT_EQ(thread.queued(), 3u);
  double waited = 0, detect = 0;
  expect_same(thread.wait(0, &waited, &detect), direct, "frame 0");
  EXPECT_GT(detect, 0.0);
  // The grey frame's error, for frame 1 only; the thread goes on.
  const std::string error = error_of([&] { thread.wait(1); }, "(no error)");
  EXPECT_EQ(error, error_of([&] { detector_->detect(grey_, 2.0, 1); }, "(no error)"));
  EXPECT_NE(error, "(no error)");
  expect_same(thread.wait(2), direct_mirror, "frame 2");
  thread.submit(frame_, 4.0, 3);
  expect_same(thread.wait(3), direct, "frame 3");
}

}  // namespace
}  // namespace depot::slam
