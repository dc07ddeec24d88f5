// Pixel scores of masks, and a mask's share inside boxes.
#include "eval/mask_score.h"

#include <cmath>

#include <gtest/gtest.h>

namespace depot::eval {
namespace {

TEST(MaskScore, CountsPixels) {
  cv::Mat truth = cv::Mat::zeros(10, 10, CV_8UC1), predicted = truth.clone();
  truth(cv::Rect(0, 0, 4, 10)).setTo(255);    // 40 px
  predicted(cv::Rect(2, 0, 4, 10)).setTo(1);  // 40 px, 20 on the truth
  MaskCounts c;
  c.add(predicted, truth);
  EXPECT_EQ(c.true_positive, 20);
  EXPECT_EQ(c.false_positive, 20);
  EXPECT_EQ(c.false_negative, 20);
  EXPECT_DOUBLE_EQ(c.iou(), 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(c.precision(), 0.5);
  EXPECT_DOUBLE_EQ(c.recall(), 0.5);
  EXPECT_TRUE(std::isnan(MaskCounts{}.iou()));
  EXPECT_THROW(c.add(predicted, cv::Mat::zeros(5, 5, CV_8UC1)), std::exception);
}

TEST(MaskScore, ShareOfTheMaskInsideBoxes) {
  cv::Mat mask = cv::Mat::zeros(20, 20, CV_8UC1);
  mask(cv::Rect(0, 0, 10, 10)).setTo(255);  // 100 px
  const BoxCoverage c = box_coverage(mask, {cv::Rect2f(5, 0, 10, 20), cv::Rect2f(8, 0, 4, 4)});
  EXPECT_EQ(c.mask_pixels, 100);
  EXPECT_EQ(c.box_pixels, 200) << "overlapping boxes count once";
  EXPECT_EQ(c.mask_in_boxes, 50);
  EXPECT_DOUBLE_EQ(c.inside(), 0.5);
  EXPECT_DOUBLE_EQ(c.covered(), 0.25);
}

}  // namespace
}  // namespace depot::eval
