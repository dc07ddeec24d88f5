#include "sim/sensor/depth_artefacts.h"

#include <algorithm>
#include <cmath>

#include "common/rng.h"

namespace depot::sim {

namespace {

// A jump between neighbours larger than this (plus 3 % of the depth) is a
// depth edge: the two surfaces are not one.
constexpr float kEdgeJump = 0.05f;
// Brightness (grey) from which a surface reflects enough infrared.
constexpr double kDarkGrey = 64.0;

bool is_edge(float a, float b) {
  return a > 0 && b > 0 && std::abs(a - b) > kEdgeJump + 0.03f * std::min(a, b);
}

}  // namespace

void apply_depth_artefacts(cv::Mat& depth, const cv::Mat& bgr, const SensorSpec& sensor,
                           uint64_t seed) {
  if (sensor.flying_pixels > 0) {
    Rng rng(derive_seed(seed, 0xf1));
    const cv::Mat exact = depth.clone();
    for (int y = 1; y + 1 < exact.rows; ++y) {
      for (int x = 1; x + 1 < exact.cols; ++x) {
        const float z = exact.at<float>(y, x);
        // The farther of the 4 neighbours across an edge from a near pixel,
        // or the nearer from a far one: the other surface this pixel sees.
        float other = 0;
        for (const auto& [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
          const float n = exact.at<float>(y + dy, x + dx);
          if (is_edge(z, n) && (other == 0 || std::abs(n - z) > std::abs(other - z))) other = n;
        }
        if (other == 0 || rng.uniform() >= sensor.flying_pixels) continue;
        const double mix = rng.uniform(0.1, 0.9);
        depth.at<float>(y, x) = static_cast<float>((1 - mix) * z + mix * other);
      }
    }
  }
  if (sensor.dark_dropout > 0) {
    Rng rng(derive_seed(seed, 0xda));
    for (int y = 0; y < depth.rows; ++y) {
      float* d = depth.ptr<float>(y);
      const cv::Vec3b* c = bgr.ptr<cv::Vec3b>(y);
      for (int x = 0; x < depth.cols; ++x) {
        const double grey = 0.114 * c[x][0] + 0.587 * c[x][1] + 0.299 * c[x][2];
        if (grey >= kDarkGrey || d[x] <= 0) continue;
        const double darkness = 1.0 - grey / kDarkGrey;
        if (rng.uniform() < sensor.dark_dropout * darkness * darkness) d[x] = 0.0f;
      }
    }
  }
}

cv::Mat misregister_depth(const cv::Mat& depth, const SensorSpec& sensor) {
  const int dx = static_cast<int>(std::lround(sensor.misregistration.x()));
  const int dy = static_cast<int>(std::lround(sensor.misregistration.y()));
  if (dx == 0 && dy == 0) return depth;
  // Whole pixels: a depth camera's registration error is a shift of its
  // pixel grid, and depth must not be blended across edges.
  cv::Mat out(depth.size(), CV_32F, cv::Scalar(0));
  const int w = depth.cols, h = depth.rows;
  const cv::Rect from(std::max(0, -dx), std::max(0, -dy), w - std::abs(dx), h - std::abs(dy));
  const cv::Rect to(std::max(0, dx), std::max(0, dy), from.width, from.height);
  if (from.width > 0 && from.height > 0) depth(from).copyTo(out(to));
  return out;
}

}  // namespace depot::sim
