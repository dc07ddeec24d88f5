#pragma once
// YOLOv5-style letterbox: resize keeping the aspect ratio, then pad
// symmetrically to the network's input size; and the box mappings between
// the original image and the letterboxed one.
#include <opencv2/core.hpp>

namespace depot::slam {

// original pixel p -> letterboxed pixel p * scale + (pad_x, pad_y).
struct LetterboxTransform {
  float scale = 1.0f;
  float pad_x = 0.0f, pad_y = 0.0f;  // left and top padding in letterboxed pixels
  cv::Size source, target;           // original and letterboxed image sizes
};

struct Letterboxed {
  cv::Mat image;  // target.width x target.height, same type as the input
  LetterboxTransform transform;
};

// As YOLOv5's utils/augmentations.py letterbox(auto=False, scaleup=True):
// scale = min(target.w / w, target.h / h), resized size rounded, padding split
// in two (left/top = round(d/2 - 0.1)), filled with `pad_value` in every
// channel (114 = YOLOv5's grey). Throws depot::Error for an empty image or a
// non-positive target.
Letterboxed letterbox(const cv::Mat& image, cv::Size target, double pad_value = 114.0);

// Original-image box -> letterboxed box.
cv::Rect2f to_letterbox(const cv::Rect2f& box, const LetterboxTransform& t);
// Letterboxed box -> original-image box (exact inverse of to_letterbox; no
// clipping).
cv::Rect2f from_letterbox(const cv::Rect2f& box, const LetterboxTransform& t);

// `box` clipped to a width x height image (empty boxes keep zero size).
cv::Rect2f clip_box(const cv::Rect2f& box, cv::Size image);

}  // namespace depot::slam
