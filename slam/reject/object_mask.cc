#include "slam/reject/object_mask.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>
#include <opencv2/imgproc.hpp>

#include "common/fast_circle.h"

namespace depot::slam {

bool ObjectMask::on_object(int x, int y) const {
  if (!valid() || !region.contains(cv::Point(x, y))) return false;
  return mask.at<uint8_t>(y - region.y, x - region.x) != 0;
}

bool ObjectMask::touches(const cv::KeyPoint& kp, float scale_factor, float reach) const {
  if (!valid()) return false;
  // Quick rejection: the circle's bounding square misses the region.
  const float scale = fast_circle_scale(kp, scale_factor, reach);
  const float r = 3 * scale + 1;
  if (kp.pt.x + r < region.x || kp.pt.y + r < region.y || kp.pt.x - r >= region.br().x ||
      kp.pt.y - r >= region.br().y)
    return false;
  if (on_object(static_cast<int>(std::lround(kp.pt.x)), static_cast<int>(std::lround(kp.pt.y))))
    return true;
  if (reach <= 0) return false;
  return fast_circle_touches(kp, scale, [this](int x, int y) { return on_object(x, y); });
}

cv::Rect2f ObjectMask::bounds() const {
  if (!valid()) return {};
  const cv::Rect r = cv::boundingRect(mask);
  return {static_cast<float>(r.x + region.x), static_cast<float>(r.y + region.y),
          static_cast<float>(r.width), static_cast<float>(r.height)};
}

namespace {

// The object's depth: the nearest strong peak of the box's depth histogram
// (a detected object stands in front of what its box also holds). Each bin
// is scored by the pixels within half the object's thickness of it; the
// object's peak is the nearest local maximum scoring at least
// `peak_share` of the best one. Returns the median depth of that window, or
// 0 when fewer than `min_pixels` of the box have depth.
// `skip(x, y)`: image pixels to leave out (the support plane).
template <typename Skip>
float object_depth(const cv::Mat& depth, const cv::Rect& box, const ObjectMaskParams& p,
                   Skip skip) {
  std::vector<float> values;
  const int step = std::max(2, p.stride);  // every other pixel is plenty for a histogram
  for (int y = box.y; y < box.y + box.height; y += step)
    for (int x = box.x; x < box.x + box.width; x += step) {
      const float d = depth.at<float>(y, x);
      if (d > 0 && std::isfinite(d) && !skip(x, y)) values.push_back(d);
    }
  if (static_cast<int>(values.size()) < p.min_seed_pixels / (step * step) + 1) return 0;
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  const int bins = std::min(4000, static_cast<int>((*hi - *lo) / p.bin_m) + 1);
  std::vector<int> hist(bins, 0);
  for (float d : values) hist[std::min(bins - 1, static_cast<int>((d - *lo) / p.bin_m))]++;
  const int half = std::max(1, static_cast<int>(std::lround(p.seed_band_m / p.bin_m)));
  std::vector<int> prefix(bins + 1, 0);
  for (int b = 0; b < bins; ++b) prefix[b + 1] = prefix[b] + hist[b];
  auto score = [&](int b) {
    return prefix[std::min(bins, b + half + 1)] - prefix[std::max(0, b - half)];
  };
  int best = 0;
  for (int b = 0; b < bins; ++b) best = std::max(best, score(b));
  int peak = 0;
  for (int b = 0; b < bins; ++b) {
    if (score(b) < p.peak_share * best) continue;
    peak = b;
    while (peak + 1 < bins && score(peak + 1) >= score(peak)) ++peak;  // climb to its top
    break;
  }
  const float w_lo = *lo + (peak - half) * p.bin_m, w_hi = *lo + (peak + half + 1) * p.bin_m;
  std::vector<float> window;
  for (float d : values)
    if (d >= w_lo && d < w_hi) window.push_back(d);
  std::nth_element(window.begin(), window.begin() + window.size() / 2, window.end());
  return window[window.size() / 2];
}

// The support plane of the region (see the header), as a mask of its
// pixels on the stride grid (255 = on the plane); empty when there is none:
// no plane holds `plane_min_share` of the region, or the plane does not
// recede (its pixels span less than `plane_min_depth_range` in depth: it may
// be the object itself, e.g. a torso; a floor runs on behind the object).
cv::Mat support_plane(const cv::Mat& depth, const cv::Rect& region, int s, int gw, int gh,
                      const PinholeCamera& camera, const ObjectMaskParams& p) {
  std::vector<Eigen::Vector3d> samples;
  const int step = std::max(1, 8 / s);            // plane fitting on every 8th pixel
  for (int gy = gh * 2 / 3; gy < gh; gy += step)  // the bottom third: where a support is
    for (int gx = 0; gx < gw; gx += step) {
      const int u = region.x + gx * s, v = region.y + gy * s;
      const float d = depth.at<float>(v, u);
      if (d > 0 && std::isfinite(d)) samples.push_back(camera.unproject(u, v, d));
    }
  if (samples.size() < 50) return {};
  cv::RNG rng(0x5eed);  // fixed: the same frame segments the same way
  auto tolerance = [&](double z) { return p.plane_tolerance_m + p.plane_tolerance_per_m * z; };
  Eigen::Vector3d best_n(0, 0, 0);
  double best_c = 0;
  size_t best_inliers = 0;
  for (int it = 0; it < p.plane_iterations; ++it) {
    const auto& a = samples[rng.uniform(0, static_cast<int>(samples.size()))];
    const auto& b = samples[rng.uniform(0, static_cast<int>(samples.size()))];
    const auto& c = samples[rng.uniform(0, static_cast<int>(samples.size()))];
    Eigen::Vector3d n = (b - a).cross(c - a);
    if (n.norm() < 1e-9) continue;
    n.normalize();
    const double off = -n.dot(a);
    size_t inliers = 0;
    for (const Eigen::Vector3d& q : samples)
      inliers += std::fabs(n.dot(q) + off) <= tolerance(q.z());
    if (inliers > best_inliers) best_inliers = inliers, best_n = n, best_c = off;
  }
  if (best_inliers < p.plane_min_share * samples.size()) return {};
  std::vector<double> z;
  for (const Eigen::Vector3d& q : samples)
    if (std::fabs(best_n.dot(q) + best_c) <= tolerance(q.z())) z.push_back(q.z());
  std::sort(z.begin(), z.end());
  if (z[z.size() * 9 / 10] - z[z.size() / 10] < p.plane_min_depth_range) return {};
  // n . X(u, v, d) + c = d (n_x (u - cx) / fx + n_y (v - cy) / fy + n_z) + c:
  // per-column and per-row terms, so marking costs a few operations a pixel.
  std::vector<float> column(gw);
  for (int gx = 0; gx < gw; ++gx)
    column[gx] =
        static_cast<float>(best_n.x() * (region.x + gx * s - camera.cx) / camera.fx + best_n.z());
  const float c = static_cast<float>(best_c);
  const float tol0 = p.plane_tolerance_m, tol1 = p.plane_tolerance_per_m;
  cv::Mat plane(gh, gw, CV_8U, cv::Scalar(0));
  for (int gy = 0; gy < gh; ++gy) {
    const int v = region.y + gy * s;
    const float row = static_cast<float>(best_n.y() * (v - camera.cy) / camera.fy);
    const float* d = depth.ptr<float>(v) + region.x;
    uint8_t* out = plane.ptr<uint8_t>(gy);
    for (int gx = 0; gx < gw; ++gx) {
      const float z = d[gx * s];
      if (z > 0 && std::fabs(z * (column[gx] + row) + c) <= tol0 + tol1 * z) out[gx] = 255;
    }
  }
  // Only the plane's parts that reach the region's bottom edge: the floor
  // runs on below the object; a coplanar patch elsewhere may be the object.
  cv::Mat components;
  const int n = cv::connectedComponents(plane, components, 4, CV_32S);
  std::vector<uint8_t> touches_bottom(n, 0);
  for (int gx = 0; gx < gw; ++gx) touches_bottom[components.at<int>(gh - 1, gx)] = 1;
  for (int gy = 0; gy < gh; ++gy)
    for (int gx = 0; gx < gw; ++gx)
      if (plane.at<uint8_t>(gy, gx) && !touches_bottom[components.at<int>(gy, gx)])
        plane.at<uint8_t>(gy, gx) = 0;
  return plane;
}

}  // namespace

cv::Rect search_region(const cv::Rect2f& box, cv::Size image, float grow) {
  const float gx = grow * box.width, gy = grow * box.height;
  return cv::Rect(cv::Point(static_cast<int>(std::floor(box.x - gx)),
                            static_cast<int>(std::floor(box.y - gy))),
                  cv::Point(static_cast<int>(std::ceil(box.x + box.width + gx)),
                            static_cast<int>(std::ceil(box.y + box.height + gy)))) &
         cv::Rect(cv::Point(0, 0), image);
}

ObjectMask with_segmentation(const ObjectMask& from_depth, const cv::Mat& segmentation,
                             const cv::Rect2f& box, const ObjectMaskParams& p, bool union_) {
  ObjectMask out;
  out.depth = from_depth.depth;
  out.region = search_region(box, segmentation.size(), p.grow);
  if (out.region.empty()) return out;
  out.mask = segmentation(out.region).clone();
  if (union_ && from_depth.valid()) {
    const cv::Rect common = out.region & from_depth.region;
    cv::Mat dst = out.mask(common - out.region.tl());
    cv::bitwise_or(dst, from_depth.mask(common - from_depth.region.tl()), dst);
  }
  if (cv::countNonZero(out.mask) == 0) out.mask.release();
  return out;
}

ObjectMask segment_object(const cv::Mat& depth, const cv::Rect2f& box, const ObjectMaskParams& p,
                          const PinholeCamera* camera, float known_depth) {
  ObjectMask out;
  out.region = search_region(box, depth.size(), p.grow);
  const cv::Rect inner = search_region(box, depth.size(), 0.0f);
  if (out.region.empty() || inner.empty()) return out;
  // Region growing on the stride grid of the search region, off its
  // support plane.
  const int s = std::max(1, p.stride);
  const int gw = (out.region.width + s - 1) / s, gh = (out.region.height + s - 1) / s;
  const cv::Mat plane = camera && p.remove_plane
                            ? support_plane(depth, out.region, s, gw, gh, *camera, p)
                            : cv::Mat();
  const uint8_t* plane_cells = plane.empty() ? nullptr : plane.ptr<uint8_t>();  // gh x gw
  auto on_plane = [&](int x, int y) { return plane_cells && plane_cells[y * gw + x]; };
  auto off_plane = [&](int x, int y) {
    return on_plane((x - out.region.x) / s, (y - out.region.y) / s);
  };
  // The depths on the stride grid, row-major, and the plane as a flag per cell.
  std::vector<float> grid_depth(static_cast<size_t>(gw) * gh);
  std::vector<uint8_t> blocked(grid_depth.size(), 0);
  for (int gy = 0; gy < gh; ++gy) {
    const float* d = depth.ptr<float>(out.region.y + gy * s) + out.region.x;
    const uint8_t* on = plane_cells ? plane_cells + static_cast<size_t>(gy) * gw : nullptr;
    float* gd = grid_depth.data() + static_cast<size_t>(gy) * gw;
    uint8_t* b = blocked.data() + static_cast<size_t>(gy) * gw;
    for (int gx = 0; gx < gw; ++gx) {
      gd[gx] = d[gx * s];
      b[gx] = !(gd[gx] > 0) || (on && on[gx]);
    }
  }
  const int in_x0 = (inner.x - out.region.x + s - 1) / s,
            in_y0 = (inner.y - out.region.y + s - 1) / s;
  const int in_x1 = std::min(gw, (inner.x + inner.width - out.region.x + s - 1) / s);
  const int in_y1 = std::min(gh, (inner.y + inner.height - out.region.y + s - 1) / s);
  // The region grown from the box's pixels within seed_band of `mode`, on
  // the stride grid (flat FIFO breadth-first search); empty when too few seeds.
  std::vector<int> queue;
  queue.reserve(grid_depth.size());
  auto grow = [&](float mode) {
    cv::Mat grid(gh, gw, CV_8U, cv::Scalar(0));
    uint8_t* g = grid.ptr<uint8_t>();
    queue.clear();
    for (int y = in_y0; y < in_y1; ++y)
      for (int x = in_x0; x < in_x1; ++x) {
        const int i = y * gw + x;
        if (!blocked[i] && std::fabs(grid_depth[i] - mode) <= p.seed_band_m) {
          g[i] = 255;
          queue.push_back(i);
        }
      }
    if (static_cast<int>(queue.size()) < p.min_seed_pixels / (s * s) + 1) return cv::Mat();
    for (size_t head = 0; head < queue.size(); ++head) {
      const int c = queue[head], cx = c % gw, cy = c / gw;
      const float dc = grid_depth[c];
      const float max_step = (p.edge_step_m + p.edge_step_per_m * dc) * s;
      const int neighbours[4] = {cx + 1 < gw ? c + 1 : -1, cx > 0 ? c - 1 : -1,
                                 cy + 1 < gh ? c + gw : -1, cy > 0 ? c - gw : -1};
      for (int n : neighbours) {
        if (n < 0 || g[n] || blocked[n]) continue;
        const float dn = grid_depth[n];
        if (std::fabs(dn - mode) > p.extent_m || std::fabs(dn - dc) > max_step) continue;
        g[n] = 255;
        queue.push_back(n);
      }
    }
    return grid;
  };
  // The box's top rows (middle columns): a box is tight around its object,
  // whose top (a head, a back) reaches the box's top edge.
  const int top_w = std::max(1, static_cast<int>(std::lround(p.top_columns * inner.width)));
  const cv::Rect top(inner.x + (inner.width - top_w) / 2, inner.y, top_w,
                     std::max(1, static_cast<int>(std::lround(p.top_rows * inner.height))));
  auto reaches_top = [&](const cv::Mat& grid) {
    int on = 0, all = 0;
    for (int y = top.y; y < top.y + top.height; y += s)
      for (int x = top.x; x < top.x + top.width; x += s) {
        const int gx_ = (x - out.region.x) / s, gy_ = (y - out.region.y) / s;
        if (gx_ >= gw || gy_ >= gh) continue;
        ++all;
        on += grid.at<uint8_t>(gy_, gx_) != 0;
      }
    return all > 0 && on >= p.top_min_share * all;
  };
  // The share of the search region outside the box that a region covers: an
  // object the box holds covers little of it, a wall behind the box much.
  auto spill = [&](const cv::Mat& grid) {
    int on = 0, all = 0;
    for (int gy = 0; gy < gh; ++gy)
      for (int gx = 0; gx < gw; ++gx) {
        if (gy >= in_y0 && gy < in_y1 && gx >= in_x0 && gx < in_x1) continue;
        ++all;
        on += grid.at<uint8_t>(gy, gx) != 0;
      }
    return all > 0 ? static_cast<float>(on) / all : 0.0f;
  };
  float mode = known_depth > 0 ? known_depth : object_depth(depth, inner, p, off_plane);
  if (mode <= 0) return out;
  cv::Mat grid = grow(mode);
  if (known_depth <= 0 && p.top_min_share > 0 && (grid.empty() || !reaches_top(grid))) {
    // The nearest object does not reach the box's top: an occluder standing
    // before the detected object (a monitor before a seated person). The
    // object is the one at the depth of the box's top.
    const float top_mode = object_depth(depth, top, p, off_plane);
    if (top_mode > 0 && top_mode - mode > p.seed_band_m &&
        top_mode - mode <= p.max_occluder_gap_m) {
      cv::Mat top_grid = grow(top_mode);
      if (!top_grid.empty() && spill(top_grid) <= p.max_spill) grid = top_grid, mode = top_mode;
    }
  }
  if (grid.empty()) return out;
  // Close pinholes (sensor noise, missing depth inside the object), then
  // back to image pixels.
  cv::morphologyEx(grid, grid, cv::MORPH_CLOSE,
                   cv::getStructuringElement(cv::MORPH_RECT, cv::Size(3, 3)));
  if (s == 1) {
    out.mask = grid;  // already the region's size
  } else {
    cv::resize(grid, out.mask, cv::Size(gw * s, gh * s), 0, 0, cv::INTER_NEAREST);
    out.mask = out.mask(cv::Rect(0, 0, out.region.width, out.region.height)).clone();
  }
  out.depth = mode;
  return out;
}

}  // namespace depot::slam
