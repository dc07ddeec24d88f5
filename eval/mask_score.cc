#include "eval/mask_score.h"

#include <cmath>

#include "common/error.h"

namespace depot::eval {
namespace {

double ratio(long a, long b) {
  return b > 0 ? static_cast<double>(a) / b : NAN;
}

}  // namespace

void MaskCounts::add(const cv::Mat& predicted, const cv::Mat& truth) {
  if (predicted.type() != CV_8UC1 || truth.type() != CV_8UC1 || predicted.size() != truth.size())
    fail("mask score", "masks must be 8-bit single-channel images of one size");
  for (int y = 0; y < truth.rows; ++y) {
    const uint8_t* p = predicted.ptr<uint8_t>(y);
    const uint8_t* t = truth.ptr<uint8_t>(y);
    for (int x = 0; x < truth.cols; ++x) {
      true_positive += p[x] && t[x];
      false_positive += p[x] && !t[x];
      false_negative += !p[x] && t[x];
    }
  }
}

void MaskCounts::add(const MaskCounts& o) {
  true_positive += o.true_positive;
  false_positive += o.false_positive;
  false_negative += o.false_negative;
}

double MaskCounts::iou() const {
  return ratio(true_positive, true_positive + false_positive + false_negative);
}

double MaskCounts::precision() const {
  return ratio(true_positive, true_positive + false_positive);
}

double MaskCounts::recall() const {
  return ratio(true_positive, true_positive + false_negative);
}

double BoxCoverage::inside() const {
  return ratio(mask_in_boxes, mask_pixels);
}

double BoxCoverage::covered() const {
  return ratio(mask_in_boxes, box_pixels);
}

BoxCoverage box_coverage(const cv::Mat& mask, const std::vector<cv::Rect2f>& boxes) {
  if (mask.type() != CV_8UC1) fail("box coverage", "mask must be an 8-bit single-channel image");
  cv::Mat in_boxes = cv::Mat::zeros(mask.size(), CV_8UC1);
  const cv::Rect image(0, 0, mask.cols, mask.rows);
  for (const cv::Rect2f& b : boxes) {
    const cv::Rect r =
        cv::Rect(cv::Point(static_cast<int>(std::floor(b.x)), static_cast<int>(std::floor(b.y))),
                 cv::Point(static_cast<int>(std::ceil(b.x + b.width)),
                           static_cast<int>(std::ceil(b.y + b.height)))) &
        image;
    in_boxes(r).setTo(255);
  }
  BoxCoverage c;
  c.mask_pixels = cv::countNonZero(mask);
  c.box_pixels = cv::countNonZero(in_boxes);
  c.mask_in_boxes = cv::countNonZero(mask & in_boxes);
  return c;
}

}  // namespace depot::eval
