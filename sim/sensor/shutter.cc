#include "sim/sensor/shutter.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"

namespace depot::sim {

double ShutterTiming::row_offset(int y, int height) const {
  if (height < 2) return 0.0;
  return (static_cast<double>(y) / (height - 1) - 0.5) * readout;
}

std::vector<double> subframe_offsets(const ShutterTiming& timing, double image_motion_px) {
  if (!timing.active()) return {0.0};
  // About one sub-frame per pixel of motion, so the sum of sub-frames reads
  // as a continuous smear rather than separate copies.
  const double wanted = std::isfinite(image_motion_px) ? std::ceil(image_motion_px) + 1.0 : 1e9;
  int most = std::max(3, timing.max_subframes);
  if (most % 2 == 0) --most;
  int count = static_cast<int>(std::clamp(wanted, 3.0, static_cast<double>(most)));
  if (count % 2 == 0) ++count;  // 0 (the timestamp) is a sub-frame of its own
  const double span = timing.span();
  std::vector<double> offsets(count);
  for (int k = 0; k < count; ++k) offsets[k] = -0.5 * span + span * k / (count - 1);
  offsets[count / 2] = 0.0;  // exactly, whatever the rounding
  return offsets;
}

double camera_image_motion(const Pose& a, const Pose& b, double focal, double cx, double cy,
                           int width, int height, double depth) {
  const Pose b_from_a = b.inverse() * a;
  double most = 0.0;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const double u = 0.5 * i * (width - 1), v = 0.5 * j * (height - 1);
      const Eigen::Vector3d p((u - cx) / focal * depth, (v - cy) / focal * depth, depth);
      const Eigen::Vector3d q = b_from_a * p;
      if (q.z() < 0.05) return 1e9;  // passes the camera: as much motion as allowed
      const double du = focal * q.x() / q.z() + cx - u, dv = focal * q.y() / q.z() + cy - v;
      most = std::max(most, std::hypot(du, dv));
    }
  }
  return most;
}

namespace {

// Weights of the sub-frames in the time average of their piecewise-linear
// interpolation over [a, b] (the value at a when a == b).
std::vector<double> window_weights(const std::vector<double>& t, double a, double b) {
  const size_t n = t.size();
  std::vector<double> w(n, 0.0);
  a = std::clamp(a, t.front(), t.back());
  b = std::clamp(b, t.front(), t.back());
  if (n == 1) {
    w[0] = 1.0;
    return w;
  }
  if (b - a <= 1e-12) {
    size_t j = std::upper_bound(t.begin(), t.end(), a) - t.begin();
    j = std::clamp<size_t>(j, 1, n - 1) - 1;
    const double s = (a - t[j]) / (t[j + 1] - t[j]);
    w[j] = 1.0 - s;
    w[j + 1] = s;
    return w;
  }
  for (size_t j = 0; j + 1 < n; ++j) {
    const double u = std::max(a, t[j]), v = std::min(b, t[j + 1]);
    if (v <= u) continue;
    const double h = t[j + 1] - t[j];
    // Integral of s = (t - t_j) / h over [u, v]: the later sub-frame's share.
    const double later = ((v - t[j]) * (v - t[j]) - (u - t[j]) * (u - t[j])) / (2.0 * h);
    w[j] += (v - u) - later;
    w[j + 1] += later;
  }
  for (double& x : w) x /= (b - a);
  return w;
}

}  // namespace

cv::Mat integrate_shutter(const std::vector<cv::Mat>& subframes, const std::vector<double>& offsets,
                          const ShutterTiming& timing) {
  if (subframes.empty() || subframes.size() != offsets.size())
    fail("shutter", "sub-frames and their instants differ in number");
  const int rows = subframes.front().rows, cols = subframes.front().cols;
  const int values = cols * subframes.front().channels();
  for (const cv::Mat& s : subframes)
    if (s.type() != CV_8UC3 || s.rows != rows || s.cols != cols)
      fail("shutter", "sub-frames differ in size or type");
  cv::Mat out(rows, cols, CV_8UC3);
  std::vector<float> sum(values);
  for (int y = 0; y < rows; ++y) {
    const double mid = timing.row_offset(y, rows);
    const std::vector<double> w =
        window_weights(offsets, mid - 0.5 * timing.exposure, mid + 0.5 * timing.exposure);
    std::fill(sum.begin(), sum.end(), 0.0f);
    for (size_t k = 0; k < subframes.size(); ++k) {
      if (w[k] <= 0.0) continue;
      const float weight = static_cast<float>(w[k]);
      const uchar* in = subframes[k].ptr<uchar>(y);
      for (int i = 0; i < values; ++i) sum[i] += weight * in[i];
    }
    uchar* o = out.ptr<uchar>(y);
    for (int i = 0; i < values; ++i)
      o[i] = static_cast<uchar>(std::clamp(std::lround(sum[i]), 0L, 255L));
  }
  return out;
}

}  // namespace depot::sim
