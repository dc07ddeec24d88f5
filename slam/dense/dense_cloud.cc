#include "slam/dense/dense_cloud.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <opencv2/imgproc.hpp>

#include "common/error.h"
#include "slam/camera/lens_distortion.h"

namespace depot::slam {
namespace {

// 21 bits per axis: +-1 million voxels (20 km at 2 cm) each way.
constexpr int64_t kAxisOffset = int64_t{1} << 20;
constexpr uint64_t kAxisMask = (uint64_t{1} << 21) - 1;

uint64_t voxel_key(const Eigen::Vector3d& p, double voxel) {
  uint64_t key = 0;
  for (int k = 0; k < 3; ++k) {
    const int64_t index = static_cast<int64_t>(std::floor(p[k] / voxel)) + kAxisOffset;
    key = (key << 21) | (static_cast<uint64_t>(std::clamp<int64_t>(index, 0, kAxisMask)));
  }
  return key;
}

}  // namespace

DenseCloud::DenseCloud(const PinholeCamera& camera, const DenseCloudParams& params)
    : camera_(camera), params_(params) {
  if (camera_.distorted()) {
    // Each pixel's undistorted position, once: depth pixels are rays of the
    // distorted image.
    std::vector<cv::Point2f> pixels;
    pixels.reserve(static_cast<size_t>(camera_.width) * camera_.height);
    for (int v = 0; v < camera_.height; ++v)
      for (int u = 0; u < camera_.width; ++u) pixels.emplace_back(u, v);
    undistorted_ = undistort_pixels(camera_, pixels);
  }
  auto check = [](bool ok, const std::string& what) {
    if (!ok) fail("dense map", what);
  };
  check(std::isfinite(params.voxel_m) && params.voxel_m >= 0.001f && params.voxel_m <= 1.0f,
        "voxel size must be in [0.001, 1] m");
  check(std::isfinite(params.max_depth_m) && params.max_depth_m > 0 && params.max_depth_m <= 100,
        "maximum depth must be in (0, 100] m");
  check(params.stride >= 1 && params.stride <= 64, "stride must be in [1, 64] px");
  check(params.mask_margin_px >= 0 && params.mask_margin_px <= 100,
        "mask margin must be in [0, 100] px");
  check(params.min_views >= 1, "minimum views must be at least 1");
  check(std::isfinite(params.free_margin_m) && params.free_margin_m >= 0 &&
            std::isfinite(params.free_margin_per_m) && params.free_margin_per_m >= 0,
        "free-space margins must be finite and not negative");
}

void DenseCloud::add_view(const Pose& T_wc, const cv::Mat& depth, const cv::Mat& bgr,
                          const cv::Mat& moving) {
  const cv::Size size(camera_.width, camera_.height);
  if (depth.type() != CV_32F || depth.size() != size || bgr.type() != CV_8UC3 ||
      bgr.size() != size || (!moving.empty() && (moving.type() != CV_8U || moving.size() != size)))
    fail("dense map", "a keyframe's images are not the camera's size and type");
  cv::Mat left_out;
  if (!moving.empty() && params_.mask_margin_px > 0) {
    const int d = 2 * params_.mask_margin_px + 1;
    cv::dilate(moving, left_out, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(d, d)));
  } else {
    left_out = moving;
  }
  const int view = views_++;
  if (params_.free_space) {
    DepthView kept{T_wc.inverse(), cv::Mat(), cv::Mat()};
    const cv::Size grid((depth.cols + params_.stride - 1) / params_.stride,
                        (depth.rows + params_.stride - 1) / params_.stride);
    cv::resize(depth, kept.depth, grid, 0, 0, cv::INTER_NEAREST);
    if (!left_out.empty()) cv::resize(left_out, kept.moving, grid, 0, 0, cv::INTER_NEAREST);
    depth_views_.push_back(std::move(kept));
  }
  const double voxel = params_.voxel_m;
  const Eigen::Matrix3d R = T_wc.linear();
  const Eigen::Vector3d t = T_wc.translation();
  for (int v = 0; v < depth.rows; v += params_.stride) {
    const float* z_row = depth.ptr<float>(v);
    const cv::Vec3b* colour_row = bgr.ptr<cv::Vec3b>(v);
    const uint8_t* out_row = left_out.empty() ? nullptr : left_out.ptr<uint8_t>(v);
    for (int u = 0; u < depth.cols; u += params_.stride) {
      const float z = z_row[u];
      if (!(z > 0 && z <= params_.max_depth_m)) continue;
      if (out_row && out_row[u]) continue;
      const cv::Point2f q = undistorted_.empty()
                                ? cv::Point2f(static_cast<float>(u), static_cast<float>(v))
                                : undistorted_[static_cast<size_t>(v) * camera_.width + u];
      const Eigen::Vector3d p = R * camera_.unproject(q.x, q.y, z) + t;
      Voxel& cell = voxels_[voxel_key(p, voxel)];
      cell.sum += p;
      const cv::Vec3b& c = colour_row[u];
      cell.colour_sum += Eigen::Vector3i(c[0], c[1], c[2]);
      ++cell.samples;
      if (cell.last_view != view) {
        cell.last_view = view;
        ++cell.views;
      }
    }
  }
}

std::pair<int, int> DenseCloud::free_and_seen(const Eigen::Vector3d& p) const {
  int free = 0, seen = 0;
  const double stride = params_.stride;
  for (const DepthView& view : depth_views_) {
    const Eigen::Vector3d c = view.T_cw * p;
    if (c.z() <= 0) continue;
    const Eigen::Vector2d uv = camera_.project(c);
    const cv::Point2f pixel =
        distort_pixel(camera_, cv::Point2f(static_cast<float>(uv.x()), static_cast<float>(uv.y())));
    const int u = static_cast<int>(std::lround(pixel.x / stride));
    const int v = static_cast<int>(std::lround(pixel.y / stride));
    if (u < 0 || v < 0 || u >= view.depth.cols || v >= view.depth.rows) continue;
    const float d = view.depth.at<float>(v, u);
    if (!(d > 0)) continue;
    const double margin = params_.free_margin_m + params_.free_margin_per_m * c.z();
    if (d > c.z() + margin)
      ++free;
    else if (d >= c.z() - margin)
      ++(!view.moving.empty() && view.moving.at<uint8_t>(v, u) ? free : seen);
  }
  return {free, seen};
}

std::vector<PlyPoint> DenseCloud::points() const {
  std::vector<uint64_t> keys;
  keys.reserve(voxels_.size());
  for (const auto& [key, cell] : voxels_) {
    if (cell.views < params_.min_views) continue;
    if (params_.free_space) {
      const auto [free, seen] = free_and_seen(cell.sum / cell.samples);
      if (free >= seen) continue;
    }
    keys.push_back(key);
  }
  std::sort(keys.begin(), keys.end());
  std::vector<PlyPoint> out;
  out.reserve(keys.size());
  for (uint64_t key : keys) {
    const Voxel& cell = voxels_.at(key);
    PlyPoint p;
    p.position = (cell.sum / cell.samples).cast<float>();
    for (int k = 0; k < 3; ++k)
      p.bgr[k] = static_cast<uint8_t>((cell.colour_sum[k] + cell.samples / 2) / cell.samples);
    p.count = cell.views;
    out.push_back(p);
  }
  return out;
}

}  // namespace depot::slam
