#pragma once
// One rule for image sizes everywhere (rendering, datasets, SLAM settings):
// each side 32..4096 px. Below 32 px no ORB keypoint survives the border;
// above 4096 px the off-screen renderer's buffers and the tracker's grids
// are not meant for it.
#include <string>

#include "common/error.h"

namespace depot {

inline constexpr int kMinImageSide = 32;
inline constexpr int kMaxImageSide = 4096;

inline bool image_size_ok(int width, int height) {
  return width >= kMinImageSide && width <= kMaxImageSide && height >= kMinImageSide &&
         height <= kMaxImageSide;
}

// Throws Error("<where>: ...") naming the size and the rule.
inline void check_image_size(int width, int height, const std::string& where) {
  if (!image_size_ok(width, height))
    fail(where, "image size " + std::to_string(width) + "x" + std::to_string(height) +
                    " is outside the supported range (each side " + std::to_string(kMinImageSide) +
                    ".." + std::to_string(kMaxImageSide) + " px)");
}

}  // namespace depot
