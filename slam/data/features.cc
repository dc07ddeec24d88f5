#include "slam/data/features.h"

#include <cmath>

#include "slam/camera/lens_distortion.h"

namespace depot::slam {

Features::Features(std::vector<cv::KeyPoint> kps, cv::Mat desc, const cv::Mat& depth_image,
                   const PinholeCamera& cam, const ScaleLevels* lv)
    : keypoints(std::move(kps)), descriptors(std::move(desc)), levels(lv), camera(cam) {
  const size_t n = keypoints.size();
  depth.assign(n, -1.0f);
  for (size_t i = 0; i < n; ++i) {
    const int x = static_cast<int>(std::lround(keypoints[i].pt.x));
    const int y = static_cast<int>(std::lround(keypoints[i].pt.y));
    if (x < 0 || y < 0 || x >= depth_image.cols || y >= depth_image.rows) continue;
    const float z = depth_image.at<float>(y, x);
    if (z > 0 && std::isfinite(z)) depth[i] = z;
  }
  // From here on keypoints live in the undistorted pinhole.
  if (camera.distorted()) {
    std::vector<cv::Point2f> pixels(n);
    for (size_t i = 0; i < n; ++i) pixels[i] = keypoints[i].pt;
    const std::vector<cv::Point2f> undistorted = undistort_pixels(camera, pixels);
    for (size_t i = 0; i < n; ++i) keypoints[i].pt = undistorted[i];
  }
  index();
}

Features::Features(std::vector<cv::KeyPoint> kps, cv::Mat desc, std::vector<float> keypoint_depth,
                   const PinholeCamera& cam, const ScaleLevels* lv)
    : keypoints(std::move(kps)),
      descriptors(std::move(desc)),
      depth(std::move(keypoint_depth)),
      levels(lv),
      camera(cam) {
  depth.resize(keypoints.size(), -1.0f);
  for (float& z : depth)
    if (!(z > 0) || !std::isfinite(z)) z = -1.0f;
  index();
}

void Features::set_colours(const cv::Mat& bgr) {
  colours.assign(keypoints.size(), cv::Vec3b(0, 0, 0));
  if (bgr.type() != CV_8UC3) return;
  for (size_t i = 0; i < keypoints.size(); ++i) {
    const cv::Point2f pixel = distort_pixel(camera, keypoints[i].pt);
    const int x = static_cast<int>(std::lround(pixel.x));
    const int y = static_cast<int>(std::lround(pixel.y));
    if (x >= 0 && y >= 0 && x < bgr.cols && y < bgr.rows) colours[i] = bgr.at<cv::Vec3b>(y, x);
  }
}

void Features::index() {
  const size_t n = keypoints.size();
  u_right.assign(n, -1.0f);
  for (size_t i = 0; i < n; ++i)
    if (depth[i] > 0) u_right[i] = static_cast<float>(camera.right_u(keypoints[i].pt.x, depth[i]));
  // The grid spans what the image shows (wider than the image for a barrel
  // lens, as ORB-SLAM2's mnMinX..mnMaxY).
  if (camera.distorted()) {
    origin_u_ = camera.min_u;
    origin_v_ = camera.min_v;
    cell_w_ = (camera.max_u - camera.min_u) / kGridCols;
    cell_h_ = (camera.max_v - camera.min_v) / kGridRows;
  } else {
    origin_u_ = origin_v_ = 0;
    cell_w_ = static_cast<double>(camera.width) / kGridCols;
    cell_h_ = static_cast<double>(camera.height) / kGridRows;
  }
  grid_.assign(kGridCols * kGridRows, {});
  for (size_t i = 0; i < n; ++i) {
    const double gx = std::floor((keypoints[i].pt.x - origin_u_) / cell_w_),
                 gy = std::floor((keypoints[i].pt.y - origin_v_) / cell_h_);
    if (!(gx >= 0 && gy >= 0 && gx < kGridCols && gy < kGridRows)) continue;
    const int cx = static_cast<int>(gx), cy = static_cast<int>(gy);
    grid_[cy * kGridCols + cx].push_back(i);
  }
}

std::vector<size_t> Features::in_area(double u, double v, double r, int min_level,
                                      int max_level) const {
  std::vector<size_t> out;
  const double gu = u - origin_u_, gv = v - origin_v_;
  const int x0 = std::max(0, static_cast<int>(std::floor((gu - r) / cell_w_)));
  const int x1 = std::min(kGridCols - 1, static_cast<int>(std::floor((gu + r) / cell_w_)));
  const int y0 = std::max(0, static_cast<int>(std::floor((gv - r) / cell_h_)));
  const int y1 = std::min(kGridRows - 1, static_cast<int>(std::floor((gv + r) / cell_h_)));
  if (x0 > x1 || y0 > y1) return out;
  for (int gy = y0; gy <= y1; ++gy)
    for (int gx = x0; gx <= x1; ++gx)
      for (size_t i : grid_[gy * kGridCols + gx]) {
        const cv::KeyPoint& kp = keypoints[i];
        if (min_level >= 0 && kp.octave < min_level) continue;
        if (max_level >= 0 && kp.octave > max_level) continue;
        const double dx = kp.pt.x - u, dy = kp.pt.y - v;
        if (dx * dx + dy * dy < r * r) out.push_back(i);
      }
  return out;
}

}  // namespace depot::slam
