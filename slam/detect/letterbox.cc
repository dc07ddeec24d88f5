#include "slam/detect/letterbox.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "common/error.h"

namespace depot::slam {

Letterboxed letterbox(const cv::Mat& image, cv::Size target, double pad_value) {
  if (image.empty()) fail("letterbox", "empty image");
  if (target.width <= 0 || target.height <= 0)
    fail("letterbox", "target size must be positive, got " + std::to_string(target.width) + "x" +
                          std::to_string(target.height));
  const double r = std::min(static_cast<double>(target.width) / image.cols,
                            static_cast<double>(target.height) / image.rows);
  const cv::Size resized(std::max(1, static_cast<int>(std::lround(image.cols * r))),
                         std::max(1, static_cast<int>(std::lround(image.rows * r))));
  const double dw = (target.width - resized.width) / 2.0;
  const double dh = (target.height - resized.height) / 2.0;
  const int top = static_cast<int>(std::lround(dh - 0.1));
  const int left = static_cast<int>(std::lround(dw - 0.1));
  const int bottom = target.height - resized.height - top;
  const int right = target.width - resized.width - left;

  Letterboxed out;
  cv::Mat scaled;
  if (resized == image.size())
    scaled = image;
  else
    cv::resize(image, scaled, resized, 0, 0, cv::INTER_LINEAR);
  cv::copyMakeBorder(scaled, out.image, top, bottom, left, right, cv::BORDER_CONSTANT,
                     cv::Scalar::all(pad_value));
  out.transform.scale = static_cast<float>(r);
  out.transform.pad_x = static_cast<float>(left);
  out.transform.pad_y = static_cast<float>(top);
  out.transform.source = image.size();
  out.transform.target = target;
  return out;
}

cv::Rect2f to_letterbox(const cv::Rect2f& box, const LetterboxTransform& t) {
  return {box.x * t.scale + t.pad_x, box.y * t.scale + t.pad_y, box.width * t.scale,
          box.height * t.scale};
}

cv::Rect2f from_letterbox(const cv::Rect2f& box, const LetterboxTransform& t) {
  return {(box.x - t.pad_x) / t.scale, (box.y - t.pad_y) / t.scale, box.width / t.scale,
          box.height / t.scale};
}

cv::Rect2f clip_box(const cv::Rect2f& box, cv::Size image) {
  const float w = static_cast<float>(image.width), h = static_cast<float>(image.height);
  const float x1 = std::clamp(box.x, 0.0f, w), y1 = std::clamp(box.y, 0.0f, h);
  const float x2 = std::clamp(box.x + box.width, 0.0f, w);
  const float y2 = std::clamp(box.y + box.height, 0.0f, h);
  return {x1, y1, std::max(0.0f, x2 - x1), std::max(0.0f, y2 - y1)};
}

}  // namespace depot::slam
