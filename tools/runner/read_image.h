#pragma once
// Reading one colour image with the project's one-line error.
#include <string>

#include <opencv2/imgcodecs.hpp>

#include "common/error.h"

namespace depot::runner {

// CV_8UC3 BGR. Throws depot::Error "<path>: missing or unreadable image".
inline cv::Mat read_colour_image(const std::string& path) {
  cv::Mat bgr = cv::imread(path, cv::IMREAD_COLOR);
  if (bgr.empty()) fail(path, "missing or unreadable image");
  return bgr;
}

}  // namespace depot::runner
