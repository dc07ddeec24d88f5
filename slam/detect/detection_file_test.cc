// The detections file: round trip, per-line errors, and replay by FileDetector.
#include "slam/detect/detection_file.h"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "common/error.h"
#include "common/testing/error_of.h"

namespace depot::slam {
namespace {

class DetectionFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = ::testing::TempDir() + "/detection_file_test_" +
           ::testing::UnitTest::GetInstance()->current_test_info()->name();
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) const {
    const std::string path = dir_ + "/" + name;
    std::ofstream(path) << text;
    return path;
  }
  static std::string read_text(const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }

  std::string dir_;
};

Detection det(const std::string& cls, float conf, float x, float y, float w, float h) {
  Detection d;
  d.class_name = cls;
  d.confidence = conf;
  d.box = cv::Rect2f(x, y, w, h);
  return d;
}

std::vector<DetectionFrame> sample_frames() {
  return {{1341846313.592026,
           {det("person", 0.87f, 310.5f, 0.f, 181.25f, 480.f),
            det("chair", 0.3141593f, 202.125f, 218.f, 82.f, 163.f)}},
          {1341846313.654184, {det("dog", 1.0f, 0.f, 1.f / 3.f, 12.7f, 9.99f)}},
          {1341846313.686156, {det("monitor", 0.0f, 639.f, 479.f, 0.f, 0.f)}}};
}

TEST_F(DetectionFileTest, RoundTripGivesTheSameDetections) {
  const std::vector<DetectionFrame> frames = sample_frames();
  const std::string path = dir_ + "/dets.txt";
  write_detections_file(path, frames);
  const std::vector<DetectionFrame> back = read_detections_file(path);
  ASSERT_EQ(back.size(), frames.size());
  for (size_t i = 0; i < frames.size(); ++i) {
    EXPECT_NEAR(back[i].timestamp, frames[i].timestamp, 1e-7);
    ASSERT_EQ(back[i].detections.size(), frames[i].detections.size());
    for (size_t k = 0; k < frames[i].detections.size(); ++k) {
      const Detection& a = frames[i].detections[k];
      const Detection& b = back[i].detections[k];
      EXPECT_EQ(b.class_name, a.class_name);
      EXPECT_EQ(b.class_id, -1);
      // Confidence and top-left corner are exact; the size is x2 - x1.
      EXPECT_EQ(b.confidence, a.confidence);
      EXPECT_EQ(b.box.x, a.box.x);
      EXPECT_EQ(b.box.y, a.box.y);
      EXPECT_FLOAT_EQ(b.box.width, a.box.width);
      EXPECT_FLOAT_EQ(b.box.height, a.box.height);
    }
  }
  // Writing what was read gives the same bytes.
  const std::string again = dir_ + "/again.txt";
  write_detections_file(again, back);
  EXPECT_EQ(read_text(again), read_text(path));
  // With a class list, class ids are the list's indices.
  const auto with_ids = read_detections_file(path, {"person", "dog", "cat", "chair", "monitor"});
  EXPECT_EQ(with_ids[0].detections[0].class_id, 0);
  EXPECT_EQ(with_ids[0].detections[1].class_id, 3);
  EXPECT_EQ(with_ids[1].detections[0].class_id, 1);
}

TEST_F(DetectionFileTest, LinesGroupIntoSortedFrames) {
  const std::string path = write("d.txt",
                                 "# made by hand\n"
                                 "\n"
                                 "2.000000 dog 0.5 1 2 3 4\r\n"
                                 "1.000000 cat 0.6 5 6 7 8\n"
                                 "   # indented comment\n"
                                 "2.000000 pig 0.7 9 10 11 12\n");
  const auto frames = read_detections_file(path);
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[0].timestamp, 1.0);
  ASSERT_EQ(frames[0].detections.size(), 1u);
  EXPECT_EQ(frames[0].detections[0].class_name, "cat");
  ASSERT_EQ(frames[1].detections.size(), 2u);
  EXPECT_EQ(frames[1].detections[0].class_name, "dog");
  EXPECT_EQ(frames[1].detections[1].class_name, "pig");
  EXPECT_EQ(frames[1].detections[1].box, cv::Rect2f(9, 10, 2, 2));
}

TEST_F(DetectionFileTest, MalformedLinesNameFileAndLine) {
  const std::string head = "# header\n1.0 person 0.9 1 2 3 4\n";
  const struct {
    const char* line;
    const char* problem;
  } cases[] = {
      {"1.0 person 0.9 1 2 3",
       "expected 7 fields (timestamp class_name confidence x1 y1 x2 y2), "
       "found 6"},
      {"1.0 person 0.9 1 2 3 4 5",
       "expected 7 fields (timestamp class_name confidence x1 y1 "
       "x2 y2), found 8"},
      {"1.0 person 0.9 nan 2 3 4", "x1 'nan' is not finite"},
      {"1.0 person 0.9 1 2 inf 4", "x2 'inf' is not finite"},
      {"1.0 person high 1 2 3 4", "confidence 'high' is not a number"},
      {"1.0 person 1.5 1 2 3 4", "confidence '1.5' is outside [0, 1]"},
      {"1.0 person 0.9 5 2 3 4", "x2 3 is left of x1 5"},
      {"1.0 person 0.9 1 5 3 4", "y2 4 is above y1 5"},
      {"-1.0 person 0.9 1 2 3 4", "timestamp '-1.0' is negative"},
      {"t1 person 0.9 1 2 3 4", "timestamp 't1' is not a number"},
      {"1.0 person 0.9 1 2 3 4x", "y2 '4x' is not a number"},
  };
  for (const auto& c : cases) {
    const std::string path = write("bad.txt", head + c.line + "\n");
    EXPECT_EQ(error_of([&] { read_detections_file(path); }), path + ":3: " + c.problem) << c.line;
  }
  const std::string path = write("unknown.txt", head + "\n1.0 horse 0.9 1 2 3 4\n");
  EXPECT_EQ(error_of([&] {
              read_detections_file(path, {"person", "dog"});
            }),
            path + ":4: unknown class 'horse'");
  EXPECT_EQ(error_of([&] { read_detections_file(dir_ + "/missing.txt"); }),
            dir_ + "/missing.txt: cannot open file");
}

TEST_F(DetectionFileTest, WritingRejectsWhatCannotBeReadBack) {
  const std::string path = dir_ + "/w.txt";
  EXPECT_NE(error_of([&] {
              write_detections_file(path, {{1.0, {det("dining table", 0.5f, 0, 0, 1, 1)}}});
            }).find("class name 'dining table' is empty or contains white space"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              write_detections_file(path, {{1.0, {det("cat", 0.5f, 0, 0, -1, 1)}}});
            }).find("negative size"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              write_detections_file(path, {{1.0, {det("cat", NAN, 0, 0, 1, 1)}}});
            }).find("non-finite"),
            std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST_F(DetectionFileTest, FileDetectorReturnsTheMatchingFrame) {
  const std::string path = dir_ + "/dets.txt";
  write_detections_file(path, sample_frames());
  FileDetector detector(path, {"person", "dog", "chair", "monitor"});
  EXPECT_EQ(detector.name(), "file:" + path);
  const cv::Mat none;
  auto d = detector.detect(none, 1341846313.654184, 1);
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].class_name, "dog");
  EXPECT_EQ(d[0].class_id, 1);
  // Within 1e-4 s on either side.
  EXPECT_EQ(detector.detect(none, 1341846313.654184 + 9e-5, 1).size(), 1u);
  d = detector.detect(none, 1341846313.592026 - 9e-5, 0);
  ASSERT_EQ(d.size(), 2u);
  EXPECT_EQ(d[1].class_name, "chair");
  // Absent frames give no detections.
  EXPECT_TRUE(detector.detect(none, 1341846313.654184 + 3e-4, 1).empty());
  EXPECT_TRUE(detector.detect(none, 0.0, 0).empty());
  EXPECT_TRUE(detector.detect(none, 2e9, 9).empty());
  // From memory, unsorted.
  FileDetector memory({{2.0, {det("cat", 0.4f, 1, 1, 2, 2)}}, {1.0, {}}});
  EXPECT_EQ(memory.detect(none, 2.00005, 0).size(), 1u);
  EXPECT_TRUE(memory.detect(none, 1.0, 0).empty());
  ASSERT_NE(memory.find(1.0), nullptr);
  EXPECT_EQ(memory.find(1.5), nullptr);
}

}  // namespace
}  // namespace depot::slam
