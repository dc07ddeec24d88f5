#include "sim/sensor/kinect_model.h"

#include <cmath>

#include "common/rng.h"

namespace depot::sim {
namespace {

// A cheap approximately normal variate: the sum of four uniform 16-bit lanes
// of one 64-bit draw (Irwin-Hall), scaled to unit variance.
inline double fast_normal(Rng& rng) {
  uint64_t r = rng.next_u64();
  double s = static_cast<double>(r & 0xffff) + static_cast<double>((r >> 16) & 0xffff) +
             static_cast<double>((r >> 32) & 0xffff) + static_cast<double>(r >> 48);
  // Sum of 4 U(0, 65536): mean 131070, sd 65536 * sqrt(4/12).
  return (s - 131070.0) / 37837.2;
}

}  // namespace

cv::Mat apply_depth_model(const cv::Mat& depth, const SensorSpec& sensor, double focal, uint64_t seed) {
  cv::Mat out(depth.size(), CV_32F, cv::Scalar(0));
  Rng rng(seed);
  const double fb = focal * sensor.baseline;  // disparity (px) = fb / z
  const int w = depth.cols;
  for (int y = 0; y < depth.rows; ++y) {
    const float* in = depth.ptr<float>(y);
    float* o = out.ptr<float>(y);
    // Projector shadow: the projector sits `baseline` to the right, so pixel x
    // is hidden from it when a surface at j > x satisfies
    // j - x < fb (1/z_j - 1/z_x), i.e. fb/z_j - j > fb/z_x - x. Scanning right
    // to left keeps the running maximum of fb/z_j - j.
    double best = -1e30;
    for (int x = w - 1; x >= 0; --x) {
      const double z = in[x];
      if (z <= 0.0) continue;
      const double key = fb / z - x;
      const bool shadowed = fb > 0 && best > key + 1.0;
      best = std::max(best, key);
      if (shadowed || z < sensor.min_depth || z > sensor.max_depth) continue;
      if (fb <= 0) {
        o[x] = static_cast<float>(z);
        continue;
      }
      double disparity = fb / z + sensor.disparity_noise * fast_normal(rng);
      if (sensor.disparity_step > 0) disparity = std::round(disparity / sensor.disparity_step) * sensor.disparity_step;
      if (disparity > 0) o[x] = static_cast<float>(fb / disparity);
    }
  }
  return out;
}

void apply_rgb_noise(cv::Mat& bgr, double sigma, uint64_t seed) {
  if (sigma <= 0) return;
  Rng rng(seed);
  for (int y = 0; y < bgr.rows; ++y) {
    uchar* p = bgr.ptr<uchar>(y);
    for (int i = 0; i < bgr.cols * bgr.channels(); ++i)
      p[i] = cv::saturate_cast<uchar>(p[i] + sigma * fast_normal(rng));
  }
}

cv::Mat depth_to_u16(const cv::Mat& depth, double factor) {
  cv::Mat out(depth.size(), CV_16U);
  for (int y = 0; y < depth.rows; ++y) {
    const float* in = depth.ptr<float>(y);
    uint16_t* o = out.ptr<uint16_t>(y);
    for (int x = 0; x < depth.cols; ++x) {
      const double v = std::round(in[x] * factor);
      o[x] = v <= 0 ? 0 : v >= 65535 ? 0 : static_cast<uint16_t>(v);  // beyond range = no data
    }
  }
  return out;
}

}  // namespace depot::sim
