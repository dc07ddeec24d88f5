#pragma once
// FAST-9's test circle (the 16 pixels of the Bresenham circle of radius 3)
// around a keypoint, at the keypoint's pyramid level: radius 3 *
// scale_factor^octave in image pixels. One definition for the boundary rule
// of the truth (eval/motion_truth.h) and for the rejection's object masks
// (slam/reject/object_mask.h).
#include <cmath>

#include <opencv2/core.hpp>

namespace depot {

inline constexpr int kFastCircle[16][2] = {{0, 3},  {1, 3},  {2, 2},  {3, 1},   {3, 0},   {3, -1},
                                           {2, -2}, {1, -3}, {0, -3}, {-1, -3}, {-2, -2}, {-3, -1},
                                           {-3, 0}, {-3, 1}, {-2, 2}, {-1, 3}};

// The circle's radius factor at the keypoint's level (scale_factor^octave),
// times `reach`.
inline float fast_circle_scale(const cv::KeyPoint& keypoint, float scale_factor,
                               float reach = 1.0f) {
  float scale = reach;
  for (int o = 0; o < keypoint.octave; ++o) scale *= scale_factor;
  return scale;
}

// True when `hit(x, y)` holds for a pixel of the keypoint's circle, its
// radius scaled by `scale` (fast_circle_scale).
template <typename Hit>
bool fast_circle_touches(const cv::KeyPoint& keypoint, float scale, Hit hit) {
  for (const auto& d : kFastCircle)
    if (hit(static_cast<int>(std::lround(keypoint.pt.x + scale * d[0])),
            static_cast<int>(std::lround(keypoint.pt.y + scale * d[1]))))
      return true;
  return false;
}

}  // namespace depot
