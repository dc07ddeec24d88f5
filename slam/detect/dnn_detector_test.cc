// The real detectors on the real TUM fr3/walking_xyz frame (two people), and
// their errors for missing or corrupt model files and mismatched class lists.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <random>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "common/error.h"
#include "common/testing/error_of.h"
#include "dataset/class_list.h"
#include "slam/detect/detector_config.h"
#include "slam/detect/detector_factory.h"
#include "slam/detect/nms.h"
#include "slam/detect/test_support.h"

namespace depot::slam {
namespace {

DetectorConfig yolo_fastest() {
  DetectorConfig c;
  c.type = "darknet";
  c.config = test::yolo_fastest_dir() + "/yolo-fastest-1.1.cfg";
  c.model = test::yolo_fastest_dir() + "/yolo-fastest-1.1.weights";
  c.names = test::yolo_fastest_dir() + "/coco.names";
  return c;
}

DetectorConfig fastestdet() {
  DetectorConfig c;
  c.type = "fastestdet";
  c.model = test::fastestdet_dir() + "/FastestDet.onnx";
  c.names = test::fastestdet_dir() + "/coco.names";
  return c;
}

// The message of the depot::Error `f` throws ("(no error)" if none).
template <typename F>
std::string error_of(F f) {
  return depot::error_of(f, "(no error)");
}

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

// Both people of the walking_xyz frame: the one sitting at the desk on the
// left, the one standing on the right.
void expect_both_people(const std::vector<Detection>& dets, float min_confidence) {
  std::vector<Detection> people;
  for (const Detection& d : dets) {
    if (d.class_name == "person" && d.confidence > min_confidence) people.push_back(d);
    EXPECT_GE(d.box.x, 0.0f);
    EXPECT_GE(d.box.y, 0.0f);
    EXPECT_LE(d.box.x + d.box.width, 640.0f);
    EXPECT_LE(d.box.y + d.box.height, 480.0f);
  }
  ASSERT_EQ(people.size(), 2u) << "persons above " << min_confidence;
  std::sort(people.begin(), people.end(),
            [](const Detection& a, const Detection& b) { return a.box.x < b.box.x; });
  for (const Detection& p : people) {
    EXPECT_GE(p.box.height, 80.0f) << p.box;
    EXPECT_GE(p.box.width, 40.0f) << p.box;
    EXPECT_EQ(p.class_id, 0);
  }
  EXPECT_LT(iou(people[0].box, people[1].box), 0.1f) << people[0].box << " " << people[1].box;
  const float left_cx = people[0].box.x + people[0].box.width / 2;
  const float right_cx = people[1].box.x + people[1].box.width / 2;
  EXPECT_LT(left_cx, 320.0f);
  EXPECT_GT(right_cx, 320.0f);
  // The standing person fills most of the frame's height.
  EXPECT_GT(people[1].box.height, 300.0f) << people[1].box;
}

class RealDetectors : public ::testing::Test {
 protected:
  void SetUp() override {
    DEPOT_REQUIRE_SHARED_DATA();
    frame_ = cv::imread(test::tum_frame(), cv::IMREAD_COLOR);
    ASSERT_FALSE(frame_.empty()) << test::tum_frame();
    ASSERT_EQ(frame_.size(), cv::Size(640, 480));
  }
  cv::Mat frame_;
};

TEST_F(RealDetectors, YoloFastestFindsBothPeople) {
  const auto det = make_dnn_detector(yolo_fastest());
  EXPECT_TRUE(contains(det->name(), "darknet")) << det->name();
  ASSERT_EQ(det->class_names().size(), 80u);
  EXPECT_EQ(det->class_names()[0], "person");
  const std::vector<Detection> dets = det->detect(frame_, 1341846313.592026, 0);
  expect_both_people(dets, 0.5f);
  // Deterministic: the same frame gives the same boxes.
  const std::vector<Detection> again = det->detect(frame_, 1341846313.592026, 1);
  ASSERT_EQ(again.size(), dets.size());
  for (size_t i = 0; i < dets.size(); ++i) EXPECT_EQ(again[i].box, dets[i].box);
}

TEST_F(RealDetectors, FastestDetFindsBothPeople) {
  DetectorConfig c = fastestdet();
  c.confidence = 0.5f;
  const auto det = make_dnn_detector(c);
  EXPECT_TRUE(contains(det->name(), "fastestdet")) << det->name();
  expect_both_people(det->detect(frame_, 0, 0), 0.5f);
}

TEST_F(RealDetectors, ShippedConfigsRunAndClassFilterKeepsOnlyWanted) {
  for (const char* yaml : {"yolo_fastest.yaml", "fastestdet.yaml"}) {
    DetectorConfig c =
        load_detector_config(test::source_dir() + "/scenes/detectors/" + std::string(yaml));
    const auto all = make_dnn_detector(c)->detect(frame_, 0, 0);
    expect_both_people(all, 0.5f);
    c.classes = {"person"};
    const auto people = make_dnn_detector(c)->detect(frame_, 0, 0);
    ASSERT_FALSE(people.empty()) << yaml;
    for (const Detection& d : people) EXPECT_EQ(d.class_name, "person") << yaml;
    EXPECT_LT(people.size(), all.size()) << yaml << ": the frame also shows monitors and chairs";
  }
}

TEST_F(RealDetectors, RejectsNonBgrFrames) {
  const auto det = make_dnn_detector(yolo_fastest());
  cv::Mat grey;
  cv::cvtColor(frame_, grey, cv::COLOR_BGR2GRAY);
  EXPECT_THROW(det->detect(grey, 0, 0), Error);
  EXPECT_THROW(det->detect(cv::Mat(), 0, 0), Error);
}

TEST(DnnDetectorErrors, MissingFilesAreNamed) {
  test::TempDir dir;
  for (const char* type : {"yolov5", "fastestdet", "darknet"}) {
    DetectorConfig c = fastestdet();
    c.type = type;
    c.config = test::yolo_fastest_dir() + "/yolo-fastest-1.1.cfg";
    c.model = dir.file("nope.model");
    const std::string e = error_of([&] { make_dnn_detector(c); });
    EXPECT_TRUE(contains(e, c.model) && contains(e, "not found")) << type << ": " << e;
  }
  if (!test::have_shared_data()) GTEST_SKIP() << "shared real data not found";
  DetectorConfig c = yolo_fastest();
  c.names = dir.file("missing.names");
  std::string e = error_of([&] { make_dnn_detector(c); });
  EXPECT_TRUE(contains(e, c.names)) << e;
  c = yolo_fastest();
  c.config = dir.file("missing.cfg");
  e = error_of([&] { make_dnn_detector(c); });
  EXPECT_TRUE(contains(e, c.config) && contains(e, "not found")) << e;
}

TEST(DnnDetectorErrors, CorruptModelFiles) {
  DEPOT_REQUIRE_SHARED_DATA();
  test::TempDir dir;
  for (const char* type : {"yolov5", "fastestdet"}) {
    DetectorConfig c = fastestdet();
    c.type = type;
    c.model = dir.write_random(std::string(type) + ".onnx", 4096);
    const std::string e = error_of([&] { make_dnn_detector(c); });
    EXPECT_TRUE(contains(e, c.model + ": cannot load model")) << type << ": " << e;
  }
  // Random bytes as weights (the random header is refused by OpenCV).
  for (const size_t bytes : {size_t{4096}, size_t{200000}}) {
    DetectorConfig c = yolo_fastest();
    c.model = dir.write_random("random" + std::to_string(bytes) + ".weights", bytes);
    const std::string e = error_of([&] { make_dnn_detector(c); });
    EXPECT_TRUE(contains(e, c.model + ": cannot load model")) << bytes << " bytes: " << e;
  }
  // A valid header: OpenCV reads a truncated file silently (and runs on
  // garbage); the loader compares its size with what the cfg needs.
  std::ifstream in(yolo_fastest().model, std::ios::binary);
  const std::string weights((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(weights.size(), 100000u);
  {
    DetectorConfig c = yolo_fastest();
    c.model = dir.write("truncated.weights", weights.substr(0, 100000));
    const std::string e = error_of([&] { make_dnn_detector(c); });
    EXPECT_TRUE(contains(e, c.model + ": cannot load model: weights file holds 24995 parameters") &&
                contains(e, "needs 346062"))
        << e;
  }
  {
    // Right size, random parameters: caught by the warm-up pass.
    std::string garbage = weights;
    std::mt19937 gen(7);
    for (size_t i = 20; i < garbage.size(); ++i) garbage[i] = static_cast<char>(gen() & 0xFF);
    DetectorConfig c = yolo_fastest();
    c.model = dir.write("garbage.weights", garbage);
    const std::string e = error_of([&] { make_dnn_detector(c); });
    EXPECT_EQ(e, c.model + ": model produces non-finite outputs (corrupt weights?)");
  }
  // A random cfg: no [net] size to default to, and OpenCV cannot parse it.
  DetectorConfig c = yolo_fastest();
  c.config = dir.write_random("random.cfg", 2048);
  std::string e = error_of([&] { make_dnn_detector(c); });
  EXPECT_TRUE(contains(e, c.config + ": no [net] width/height")) << e;
  c.input_width = c.input_height = 320;
  e = error_of([&] { make_dnn_detector(c); });
  EXPECT_TRUE(contains(e, c.model + ": cannot load model") && contains(e, c.config)) << e;
}

TEST(DnnDetectorErrors, NamesFileWithWrongClassCount) {
  DEPOT_REQUIRE_SHARED_DATA();
  test::TempDir dir;
  std::vector<std::string> names =
      dataset::load_class_names(test::yolo_fastest_dir() + "/coco.names");
  names.pop_back();
  std::string text;
  for (const auto& n : names) text += n + "\n";
  const std::string short_names = dir.write("short.names", text);
  for (DetectorConfig c : {yolo_fastest(), fastestdet()}) {
    c.names = short_names;
    const std::string e = error_of([&] { make_dnn_detector(c); });
    EXPECT_EQ(e, c.model + ": model outputs 80 classes but " + short_names + " lists 79");
  }
  // A wanted class the names file does not have.
  DetectorConfig c = yolo_fastest();
  c.classes = {"person", "sweeping robot"};
  const std::string e = error_of([&] { make_dnn_detector(c); });
  EXPECT_TRUE(contains(e, c.names) && contains(e, "'sweeping robot'")) << e;
}

TEST(DnnDetectorErrors, UnknownTypeInCode) {
  DetectorConfig c = fastestdet();
  c.type = "yolov9";
  const std::string e = error_of([&] { make_dnn_detector(c); });
  EXPECT_TRUE(contains(e, "unknown detector type 'yolov9'")) << e;
}

}  // namespace
}  // namespace depot::slam
