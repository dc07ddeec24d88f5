#include "sim/sensor/kinect_model.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "common/rng.h"
#include "sim/sensor/noise_table.h"

namespace depot::sim {

cv::Mat apply_depth_model(const cv::Mat& depth, const SensorSpec& sensor, double focal,
                          uint64_t seed) {
  cv::Mat out(depth.size(), CV_32F, cv::Scalar(0));
  Rng rng(seed);
  const double fb = focal * sensor.baseline;  // disparity (px) = fb / z
  const int w = depth.cols;
  // Noise and quantisation are the sensor's, specified in pixels of a
  // 640-wide image: keep them metric when rendering at another size.
  const double fb_sensor = fb * 640.0 / w;
  for (int y = 0; y < depth.rows; ++y) {
    const float* in = depth.ptr<float>(y);
    float* o = out.ptr<float>(y);
    // Projector shadow: the projector sits `baseline` to the right, so pixel x
    // is hidden from it when a surface at j > x satisfies
    // j - x < fb (1/z_j - 1/z_x), i.e. fb/z_j - j > fb/z_x - x. Scanning right
    // to left keeps the running maximum of fb/z_j - j.
    double best = -1e30;
    const int8_t* noise = noise_row(rng, w);
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
      double disparity = fb_sensor / z + sensor.disparity_noise * (noise[x] / 16.0);
      if (sensor.disparity_step > 0)
        disparity = std::round(disparity / sensor.disparity_step) * sensor.disparity_step;
      if (disparity > 0) o[x] = static_cast<float>(fb_sensor / disparity);
    }
  }
  return out;
}

void apply_rgb_noise(cv::Mat& bgr, double sigma, uint64_t seed) {
  if (sigma <= 0) return;
  Rng rng(seed);
  const int scale = static_cast<int>(std::lround(sigma * 16.0));  // fixed point, /256
  const int n = bgr.cols * bgr.channels();
  for (int y = 0; y < bgr.rows; ++y) {
    uchar* p = bgr.ptr<uchar>(y);
    const int8_t* noise = noise_row(rng, n);
    for (int i = 0; i < n; ++i) {
      const int v = p[i] + ((noise[i] * scale + (1 << 7)) >> 8);
      p[i] = static_cast<uchar>(v < 0 ? 0 : v > 255 ? 255 : v);
    }
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
