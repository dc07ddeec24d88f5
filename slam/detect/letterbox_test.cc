// YOLOv5-style letterbox: sizes, padding, and boxes mapped there and back.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "common/error.h"
#include "slam/detect/letterbox.h"

namespace depot::slam {
namespace {

// Bounding box of the pixels equal to 255 in channel 0.
cv::Rect white_box(const cv::Mat& img) {
  cv::Mat ch;
  cv::extractChannel(img, ch, 0);
  return cv::boundingRect(ch == 255);
}

TEST(Letterbox, TumFrameTo640PadsTopAndBottomWith114) {
  cv::Mat img(480, 640, CV_8UC3, cv::Scalar(10, 20, 30));
  const Letterboxed lb = letterbox(img, {640, 640});
  ASSERT_EQ(lb.image.size(), cv::Size(640, 640));
  EXPECT_EQ(lb.image.type(), CV_8UC3);
  EXPECT_FLOAT_EQ(lb.transform.scale, 1.0f);
  EXPECT_FLOAT_EQ(lb.transform.pad_x, 0.0f);
  EXPECT_FLOAT_EQ(lb.transform.pad_y, 80.0f);
  EXPECT_EQ(lb.transform.source, cv::Size(640, 480));
  EXPECT_EQ(lb.transform.target, cv::Size(640, 640));
  EXPECT_EQ(lb.image.at<cv::Vec3b>(0, 0), cv::Vec3b(114, 114, 114));
  EXPECT_EQ(lb.image.at<cv::Vec3b>(79, 639), cv::Vec3b(114, 114, 114));
  EXPECT_EQ(lb.image.at<cv::Vec3b>(80, 0), cv::Vec3b(10, 20, 30));
  EXPECT_EQ(lb.image.at<cv::Vec3b>(559, 639), cv::Vec3b(10, 20, 30));
  EXPECT_EQ(lb.image.at<cv::Vec3b>(560, 0), cv::Vec3b(114, 114, 114));
}

TEST(Letterbox, SizesAndPaddingAsYolov5) {
  // 1280x480 into 640x640: scale 0.5, 640x240, 200 px above and below.
  Letterboxed lb = letterbox(cv::Mat(480, 1280, CV_8UC3, cv::Scalar::all(0)), {640, 640});
  EXPECT_FLOAT_EQ(lb.transform.scale, 0.5f);
  EXPECT_FLOAT_EQ(lb.transform.pad_y, 200.0f);
  EXPECT_FLOAT_EQ(lb.transform.pad_x, 0.0f);
  // 480x640 (portrait) into 320x256: scale min(320/480, 256/640) = 0.4,
  // 192x256, dw = 64 -> left = right = 64.
  lb = letterbox(cv::Mat(640, 480, CV_8UC3, cv::Scalar::all(0)), {320, 256});
  EXPECT_EQ(lb.image.size(), cv::Size(320, 256));
  EXPECT_FLOAT_EQ(lb.transform.scale, 0.4f);
  EXPECT_FLOAT_EQ(lb.transform.pad_x, 64.0f);
  EXPECT_FLOAT_EQ(lb.transform.pad_y, 0.0f);
  // Odd total padding: 640x471 into 640x640 leaves 169 rows; YOLOv5 puts
  // round(84.5 - 0.1) = 84 on top and round(84.5 + 0.1) = 85 below.
  lb = letterbox(cv::Mat(471, 640, CV_8UC3, cv::Scalar::all(0)), {640, 640});
  EXPECT_FLOAT_EQ(lb.transform.pad_y, 84.0f);
  EXPECT_EQ(lb.image.at<cv::Vec3b>(83, 0), cv::Vec3b(114, 114, 114));
  EXPECT_EQ(lb.image.at<cv::Vec3b>(84, 0), cv::Vec3b(0, 0, 0));
  EXPECT_EQ(lb.image.at<cv::Vec3b>(554, 0), cv::Vec3b(0, 0, 0));
  EXPECT_EQ(lb.image.at<cv::Vec3b>(555, 0), cv::Vec3b(114, 114, 114));
  // Grey and custom pad values.
  lb = letterbox(cv::Mat(10, 20, CV_8UC1, cv::Scalar::all(0)), {20, 20}, 7);
  EXPECT_EQ(lb.image.type(), CV_8UC1);
  EXPECT_EQ(lb.image.at<uchar>(0, 0), 7);
}

TEST(Letterbox, BoxesRoundTripExactly) {
  const LetterboxTransform t =
      letterbox(cv::Mat(480, 640, CV_8UC3, cv::Scalar::all(0)), {320, 320}).transform;
  ASSERT_FLOAT_EQ(t.scale, 0.5f);
  ASSERT_FLOAT_EQ(t.pad_y, 40.0f);
  const cv::Rect2f boxes[] = {{0, 0, 640, 480}, {12.5f, 33.25f, 100, 200}, {600, 400, 39.5f, 79}};
  for (const cv::Rect2f& b : boxes) {
    const cv::Rect2f in = to_letterbox(b, t);
    const cv::Rect2f back = from_letterbox(in, t);
    EXPECT_NEAR(back.x, b.x, 1e-4);
    EXPECT_NEAR(back.y, b.y, 1e-4);
    EXPECT_NEAR(back.width, b.width, 1e-4);
    EXPECT_NEAR(back.height, b.height, 1e-4);
  }
  // Hand computed: (100, 50, 200, 100) -> (50, 65, 100, 50).
  const cv::Rect2f in = to_letterbox({100, 50, 200, 100}, t);
  EXPECT_FLOAT_EQ(in.x, 50.0f);
  EXPECT_FLOAT_EQ(in.y, 65.0f);
  EXPECT_FLOAT_EQ(in.width, 100.0f);
  EXPECT_FLOAT_EQ(in.height, 50.0f);
}

TEST(Letterbox, ImageContentLandsWhereTheMappingSays) {
  // A white rectangle on even pixel bounds: the 2x bilinear downscale keeps
  // its edges sharp, so the letterboxed image shows it exactly where
  // to_letterbox puts it, and from_letterbox maps it back to the original.
  for (const double s : {1.0, 2.0}) {
    cv::Mat img(static_cast<int>(480 * s), static_cast<int>(640 * s), CV_8UC3, cv::Scalar::all(0));
    const cv::Rect drawn(static_cast<int>(100 * s), static_cast<int>(50 * s),
                         static_cast<int>(200 * s), static_cast<int>(100 * s));
    img(drawn).setTo(cv::Scalar::all(255));
    const Letterboxed lb = letterbox(img, {640, 640});
    const cv::Rect seen = white_box(lb.image);
    const cv::Rect2f expected = to_letterbox(cv::Rect2f(drawn), lb.transform);
    EXPECT_EQ(cv::Rect2f(seen), expected) << "scale " << 1 / s;
    const cv::Rect2f back = from_letterbox(cv::Rect2f(seen), lb.transform);
    EXPECT_EQ(back, cv::Rect2f(drawn)) << "scale " << 1 / s;
  }
}

TEST(Letterbox, ClipBoxAndBadInput) {
  EXPECT_EQ(clip_box({-10, -5, 50, 50}, {640, 480}), cv::Rect2f(0, 0, 40, 45));
  EXPECT_EQ(clip_box({600, 400, 100, 100}, {640, 480}), cv::Rect2f(600, 400, 40, 80));
  EXPECT_EQ(clip_box({700, 10, 10, 10}, {640, 480}).area(), 0.0f);
  EXPECT_THROW(letterbox(cv::Mat(), {640, 640}), Error);
  EXPECT_THROW(letterbox(cv::Mat(4, 4, CV_8UC3), {0, 640}), Error);
}

}  // namespace
}  // namespace depot::slam
