#include "slam/camera/lens_distortion.h"

#include <algorithm>
#include <cmath>

#include <opencv2/calib3d.hpp>

#include "common/error.h"

namespace depot::slam {
namespace {

// OpenCV's fixed-point inversion, run until it moves less than 1e-9 of a
// focal length (its default of 5 steps leaves tenths of a pixel in the
// corners of a Kinect lens).
const cv::TermCriteria kUndistortUntil(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 100, 1e-9);

}  // namespace

cv::Matx33d opencv_camera_matrix(const PinholeCamera& c) {
  return {c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1};
}

cv::Vec<double, 5> opencv_distortion(const PinholeCamera& c) {
  return {c.lens.k1, c.lens.k2, c.lens.p1, c.lens.p2, c.lens.k3};
}

std::vector<cv::Point2f> undistort_pixels(const PinholeCamera& camera,
                                          const std::vector<cv::Point2f>& pixels) {
  if (!camera.distorted() || pixels.empty()) return pixels;
  std::vector<cv::Point2f> out;
  const cv::Matx33d k = opencv_camera_matrix(camera);
  cv::undistortPoints(pixels, out, k, opencv_distortion(camera), cv::noArray(), k, kUndistortUntil);
  return out;
}

cv::Point2f undistort_pixel(const PinholeCamera& camera, const cv::Point2f& pixel) {
  if (!camera.distorted()) return pixel;
  return undistort_pixels(camera, {pixel})[0];
}

cv::Point2f distort_pixel(const PinholeCamera& camera, const cv::Point2f& undistorted) {
  if (!camera.distorted()) return undistorted;
  const double x = (undistorted.x - camera.cx) / camera.fx;
  const double y = (undistorted.y - camera.cy) / camera.fy;
  const Eigen::Vector2d d = distort_normalised(camera.lens, {x, y});
  return {static_cast<float>(camera.fx * d.x() + camera.cx),
          static_cast<float>(camera.fy * d.y() + camera.cy)};
}

void set_undistorted_bounds(PinholeCamera& camera, const std::string& where) {
  if (!camera.distorted()) return;
  // The image's border, densely: a barrel lens bows the edges outwards.
  std::vector<cv::Point2f> border;
  const float w = static_cast<float>(camera.width), h = static_cast<float>(camera.height);
  for (int i = 0; i <= 64; ++i) {
    const float s = i / 64.0f;
    border.insert(border.end(), {{s * w, 0}, {s * w, h}, {0, s * h}, {w, s * h}});
  }
  const std::vector<cv::Point2f> undistorted = undistort_pixels(camera, border);
  camera.min_u = camera.min_v = INFINITY;
  camera.max_u = camera.max_v = -INFINITY;
  for (size_t i = 0; i < border.size(); ++i) {
    const cv::Point2f& p = undistorted[i];
    const cv::Point2f back = distort_pixel(camera, p);
    if (!(std::hypot(back.x - border[i].x, back.y - border[i].y) < 0.01))
      fail(where, "the lens distortion (" + describe_lens(camera.lens) +
                      ") does not invert at image pixel (" + std::to_string(border[i].x) + ", " +
                      std::to_string(border[i].y) + "): it folds the image");
    camera.min_u = std::min<double>(camera.min_u, p.x);
    camera.max_u = std::max<double>(camera.max_u, p.x);
    camera.min_v = std::min<double>(camera.min_v, p.y);
    camera.max_v = std::max<double>(camera.max_v, p.y);
  }
}

}  // namespace depot::slam
