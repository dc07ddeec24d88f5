// The per-keypoint file: its columns, the built-in modes' file read back
// exactly, one error per bad input, and scoring a file on a one-frame
// dataset written here.
#include "eval/keypoint_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/error.h"
#include "common/png_codec.h"
#include "eval/keypoint_score.h"
#include "eval/test_files.h"

namespace depot::eval {
namespace {

KeypointFrames two_frames() {
  KeypointFrames f;
  f.dataset = "DATASET";
  f.timestamps = {1.0, 1.033333};
  f.image = cv::Size(160, 120);
  return f;
}

// The one-line error reading `text` gives; "" when it reads.
std::string read_error(const std::string& text) {
  const std::string path = testing::write_test_file("bad.csv", text);
  try {
    read_keypoint_file(path, two_frames());
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_EQ(message.rfind(path + ":", 0), 0u) << message;  // names the file first
    return message;
  }
  return "";
}

TEST(KeypointFile, ReadsTheRequiredColumnsInAnyOrderAndIgnoresOthers) {
  const std::string path = testing::write_test_file("min.csv",
                                                    "kept,note,y,x,timestamp\n"
                                                    "1,a,10.5,20.25,1.000000\n"
                                                    "\n"
                                                    "0,b,119.9,0,1.0333330001\n");
  const KeypointFile f = read_keypoint_file(path, two_frames());
  ASSERT_EQ(f.rows.size(), 2u);
  EXPECT_FALSE(f.has_octave);
  EXPECT_FALSE(f.has_response);
  EXPECT_FALSE(f.has_set);
  EXPECT_EQ(f.rows[0].timestamp, 1.0);
  EXPECT_EQ(f.rows[0].x, 20.25f);
  EXPECT_EQ(f.rows[0].y, 10.5f);
  EXPECT_TRUE(f.rows[0].kept);
  EXPECT_EQ(f.rows[0].octave, 0);
  EXPECT_EQ(f.rows[0].line, 2u);
  EXPECT_EQ(f.rows[1].timestamp, 1.033333);  // the dataset's frame, matched to 1 us
  EXPECT_FALSE(f.rows[1].kept);
  EXPECT_EQ(f.rows[1].line, 4u);
}

TEST(KeypointFile, ReadsBackTheBuiltInModesRowsExactly) {
  std::ostringstream out;
  write_keypoint_header(out);
  WrittenKeypoint w;
  w.frame = 1;
  w.timestamp = 1.033333;
  // A point a 2-decimal file would move across a pixel edge (x 99.496 ->
  // "99.50" rounds to pixel 100).
  w.keypoint = cv::KeyPoint(99.496f, 57.123456f, 7.0f, -1.0f, 0.0f, 3);
  w.set = 'Q';
  w.kept = false;
  w.depth_m = 2.5f;
  w.truth = WrittenKeypoint::Truth{false, true, 12};
  write_keypoint_row(out, w);
  w.truth.reset();
  w.kept = true;
  write_keypoint_row(out, w);
  EXPECT_EQ(out.str().substr(0, out.str().find('\n')),
            "frame,timestamp,x,y,octave,set,kept,depth_m,on_moving,boundary,instance");
  const KeypointFile f =
      read_keypoint_file(testing::write_test_file("runner.csv", out.str()), two_frames());
  ASSERT_EQ(f.rows.size(), 2u);
  EXPECT_TRUE(f.has_octave);
  EXPECT_TRUE(f.has_set);
  EXPECT_EQ(f.rows[0].x, 99.496f);  // the same float, bit for bit
  EXPECT_EQ(f.rows[0].y, 57.123456f);
  EXPECT_EQ(f.rows[0].octave, 3);
  EXPECT_EQ(f.rows[0].set, "Q");
  EXPECT_FALSE(f.rows[0].kept);
  EXPECT_TRUE(f.rows[1].kept);  // empty truth columns on real data still read
}

TEST(KeypointFile, BadInputIsOneErrorNamingTheLine) {
  const std::string header = "timestamp,x,y,kept,octave,response\n";
  EXPECT_NE(read_error("timestamp,x,kept\n1.0,5,0\n").find(":1: the header has no 'y' column"),
            std::string::npos);
  EXPECT_NE(read_error("timestamp,x,x,y,kept\n").find("column 'x' appears twice"),
            std::string::npos);
  EXPECT_THAT(read_error(""), ::testing::HasSubstr("empty"));
  EXPECT_THAT(read_error(header), ::testing::HasSubstr("no keypoint rows"));
  EXPECT_NE(
      read_error(header + "1.0,5,5,1,0,0\n1.0,abc,5,1,0,0\n").find(":3: x is not a number: 'abc'"),
      std::string::npos);
  EXPECT_NE(read_error(header + "1.0,5,nan,1,0,0\n").find(":2: y is not a finite number: 'nan'"),
            std::string::npos);
  EXPECT_NE(read_error(header + "1.0,5,5,1,0,inf\n").find("response is not a finite number"),
            std::string::npos);
  EXPECT_NE(read_error(header + "1.0,5,5,2,0,0\n").find(":2: kept must be 0 (rejected) or 1"),
            std::string::npos);
  EXPECT_THAT(read_error(header + "1.0,5,5,,0,0\n"), ::testing::HasSubstr("kept must be 0"));
  EXPECT_NE(read_error(header + "1.0,5,5,1,-1,0\n").find("octave must be a pyramid level"),
            std::string::npos);
  EXPECT_NE(read_error(header + "1.0,5,5,1,0.5,0\n").find("octave must be a pyramid level"),
            std::string::npos);
  EXPECT_NE(
      read_error(header + "2.0,5,5,1,0,0\n").find(":2: timestamp 2.0 is not a frame of DATASET"),
      std::string::npos);
  EXPECT_NE(read_error(header + "1.0,160,5,1,0,0\n")
                .find(":2: point (160, 5) is outside the 160x120 image"),
            std::string::npos);
  EXPECT_NE(read_error(header + "1.0,5,-0.5,1,0,0\n").find("outside the 160x120 image"),
            std::string::npos);
  EXPECT_NE(
      read_error(header + "1.0,5,5,1,0\n").find(":2: expected 6 fields as the header has, got 5"),
      std::string::npos);
  EXPECT_THAT(read_error("x,y,kept,timestamp\n"), ::testing::HasSubstr("no keypoint rows"));
}

// A one-frame dataset: a moving square at x 50..89, y 30..89 (160x120).
std::string moving_square_dataset() {
  const std::string labels_txt = testing::write_test_file(
      "labels.txt", "# timestamp filename\n1.000000 labels/1.png\n1.033333 labels/1.png\n");
  const std::filesystem::path dir = std::filesystem::path(labels_txt).parent_path();
  testing::write_test_file("object_poses.txt",
                           "# timestamp id tx ty tz qx qy qz qw moving\n"
                           "1.000000 5 0 0 0 0 0 0 1 1\n"
                           "1.033333 5 0 0 0 0 0 0 1 1\n");
  cv::Mat labels(120, 160, CV_16U, cv::Scalar(1));
  labels(cv::Rect(50, 30, 40, 60)).setTo(5);
  std::filesystem::create_directories(dir / "labels");
  const std::vector<unsigned char> png = encode_png(labels, PngKind::kLabels);
  std::ofstream((dir / "labels/1.png").string(), std::ios::binary)
      .write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
  return dir.string();
}

TEST(KeypointFile, ScoresFrameByFrameAsTheBuiltInRule) {
  const MotionTruth truth(moving_square_dataset());
  // Frames interleaved; on the mover: (70,60) and (89,60); (92,60) is a
  // boundary point at octave 0; (94,60) at octave 3 one too (radius 5.2).
  const std::string path = testing::write_test_file("score.csv",
                                                    "timestamp,x,y,kept,octave\n"
                                                    "1.0,70,60,0,0\n"
                                                    "1.033333,89,60,1,0\n"
                                                    "1.0,92,60,0,0\n"
                                                    "1.033333,94,60,1,3\n"
                                                    "1.0,10,10,1,0\n");
  KeypointFrames frames = two_frames();
  frames.timestamps = truth.timestamps();
  const KeypointFileScore s = score_keypoint_file(truth, read_keypoint_file(path, frames), 1.2f);
  EXPECT_EQ(s.frames, 2u);
  EXPECT_EQ(s.keypoints, 5u);
  EXPECT_EQ(s.score.true_positive, 1);
  EXPECT_EQ(s.score.false_negative, 1);
  EXPECT_EQ(s.score.false_positive, 1);
  EXPECT_EQ(s.score.boundary_false_positive, 1);
  EXPECT_EQ(s.score.true_negative, 2);
  EXPECT_EQ(s.score.boundary_true_negative, 1);
  EXPECT_DOUBLE_EQ(s.score.precision(), 0.5);
  EXPECT_DOUBLE_EQ(s.score.precision_without_boundary(), 1.0);
  EXPECT_DOUBLE_EQ(s.score.recall(), 0.5);

  // Keeping everything: nothing rejected, precision undefined, recall 0.
  const std::string keep_all =
      testing::write_test_file("keep_all.csv", "timestamp,x,y,kept\n1.0,70,60,1\n1.0,10,10,1\n");
  const KeypointFileScore k =
      score_keypoint_file(truth, read_keypoint_file(keep_all, frames), 1.2f);
  EXPECT_TRUE(std::isnan(k.score.precision()));
  EXPECT_EQ(k.score.recall(), 0.0);
}

}  // namespace
}  // namespace depot::eval
