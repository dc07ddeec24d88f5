#include "common/png_codec.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "common/testing/error_of.h"
#include "common/testing/scratch_folder.h"

namespace depot {
namespace {

std::string write_bytes(const testkit::ScratchFolder& scratch, const std::string& name,
                        const std::vector<unsigned char>& bytes) {
  const std::string path = scratch.file(name);
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
  return path;
}

cv::Mat pattern(int type) {
  cv::Mat m(37, 53, type);
  cv::randu(m, 0, type == CV_16UC1 ? 65535 : 255);
  return m;
}

TEST(PngCodec, RoundTripsEveryKindExactly) {
  const testkit::ScratchFolder scratch("png_test");
  const struct {
    int type;
    PngKind kind;
  } cases[] = {
      {CV_8UC3, PngKind::kColor}, {CV_16UC1, PngKind::kDepth}, {CV_8UC1, PngKind::kLabels}};
  for (const auto& c : cases) {
    const cv::Mat image = pattern(c.type);
    const std::string path = write_bytes(scratch, "round", encode_png(image, c.kind, 3));
    const cv::Mat back = read_image(path, ImageRead::kUnchanged);
    ASSERT_EQ(back.type(), image.type());
    EXPECT_EQ(cv::norm(back, image, cv::NORM_INF), 0.0);
    // OpenCV reads our files the same: they are standard PNGs.
    EXPECT_EQ(cv::norm(cv::imread(path, cv::IMREAD_UNCHANGED), image, cv::NORM_INF), 0.0);
  }
}

TEST(PngCodec, ColourModeConvertsLikeOpenCv) {
  const testkit::ScratchFolder scratch("png_test");
  for (int type : {CV_8UC1, CV_16UC1, CV_8UC3}) {
    const cv::Mat image = pattern(type);
    std::vector<unsigned char> bytes;
    ASSERT_TRUE(cv::imencode(".png", image, bytes));
    const std::string path = write_bytes(scratch, "colour", bytes);
    const cv::Mat ours = read_image(path, ImageRead::kColor);
    const cv::Mat theirs = cv::imread(path, cv::IMREAD_COLOR);
    ASSERT_EQ(ours.type(), CV_8UC3);
    EXPECT_EQ(cv::norm(ours, theirs, cv::NORM_INF), 0.0) << type;
  }
}

TEST(PngCodec, DamagedAndMissingFilesAreOneErrorNamingThem) {
  const testkit::ScratchFolder scratch("png_test");
  std::vector<unsigned char> bytes = encode_png(pattern(CV_8UC3), PngKind::kColor, 0);
  bytes.resize(bytes.size() / 2);
  const std::string truncated = write_bytes(scratch, "truncated.png", bytes);
  const std::string e = error_of([&] { read_image(truncated, ImageRead::kColor); });
  EXPECT_EQ(e.rfind(truncated + ": damaged PNG (", 0), 0u) << e;

  const std::string junk =
      write_bytes(scratch, "junk.png", {'n', 'o', 't', ' ', 'a', 'n', ' ', 'i'});
  EXPECT_NE(error_of([&] { read_image(junk, ImageRead::kColor); }).find("unreadable image"),
            std::string::npos);
  EXPECT_NE(error_of([&] { read_image("/nonexistent.png", ImageRead::kColor); }).find("missing"),
            std::string::npos);
}

TEST(PngCodec, OtherFormatsGoThroughOpenCv) {
  const testkit::ScratchFolder scratch("png_test");
  std::vector<unsigned char> bytes;
  ASSERT_TRUE(cv::imencode(".jpg", pattern(CV_8UC3), bytes));
  const cv::Mat image = read_image(write_bytes(scratch, "photo.jpg", bytes), ImageRead::kColor);
  EXPECT_EQ(image.size(), cv::Size(53, 37));
}

}  // namespace
}  // namespace depot
