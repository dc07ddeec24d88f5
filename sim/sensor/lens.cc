#include "sim/sensor/lens.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>
#include <opencv2/imgproc.hpp>

#include "common/error.h"
#include "common/image_size.h"

namespace depot::sim {
namespace {

// d(distorted) / d(xy) at xy.
Eigen::Matrix2d distortion_jacobian(const LensDistortion& l, const Eigen::Vector2d& xy) {
  const double x = xy.x(), y = xy.y(), r2 = x * x + y * y;
  const double radial = 1 + r2 * (l.k1 + r2 * (l.k2 + r2 * l.k3));
  const double dradial = l.k1 + r2 * (2 * l.k2 + 3 * r2 * l.k3);  // d radial / d r2
  Eigen::Matrix2d j;
  j(0, 0) = radial + 2 * x * x * dradial + 2 * l.p1 * y + 6 * l.p2 * x;
  j(0, 1) = 2 * x * y * dradial + 2 * l.p1 * x + 2 * l.p2 * y;
  j(1, 0) = j(0, 1);
  j(1, 1) = radial + 2 * y * y * dradial + 6 * l.p1 * y + 2 * l.p2 * x;
  return j;
}

// A bilinear sample reads the pixel after the one it lands in.
constexpr int kCanvasPad = 2;

}  // namespace

double distortion_jacobian_det(const LensDistortion& lens, const Eigen::Vector2d& xy) {
  return distortion_jacobian(lens, xy).determinant();
}

bool undistort_normalised(const LensDistortion& lens, const Eigen::Vector2d& distorted,
                          Eigen::Vector2d& xy) {
  xy = distorted;
  for (int it = 0; it < 50; ++it) {
    const Eigen::Vector2d residual = distort_normalised(lens, xy) - distorted;
    if (residual.norm() < 1e-13) return true;
    const Eigen::Matrix2d j = distortion_jacobian(lens, xy);
    if (!(j.determinant() > 0)) return false;
    xy -= j.inverse() * residual;
    if (!xy.allFinite()) return false;
  }
  return (distort_normalised(lens, xy) - distorted).norm() < 1e-10;
}

bool lens_resamples(const CameraIntrinsics& camera, const LensDistortion& lens) {
  return lens.any() || camera.focal_y() != camera.f;
}

LensMapping make_lens_mapping(const CameraIntrinsics& camera, const LensDistortion& lens,
                              const std::string& where) {
  const int w = camera.width, h = camera.height;
  const double fx = camera.f, fy = camera.focal_y();
  // Each output pixel's ray; the largest radius any of them reaches.
  std::vector<Eigen::Vector2d> rays(static_cast<size_t>(w) * h);
  double max_r = 0;
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const Eigen::Vector2d d((u - camera.cx) / fx, (v - camera.cy) / fy);
      Eigen::Vector2d& xy = rays[static_cast<size_t>(v) * w + u];
      if (!undistort_normalised(lens, d, xy))
        fail(where, "the lens distortion (" + describe_lens(lens) +
                        ") folds the image: no single ray reaches pixel (" + std::to_string(u) +
                        ", " + std::to_string(v) + ")");
      max_r = std::max(max_r, xy.norm());
      x0 = std::min(x0, xy.x());
      x1 = std::max(x1, xy.x());
      y0 = std::min(y0, xy.y());
      y1 = std::max(y1, xy.y());
    }
  // The mapping must not turn back anywhere within the rays the image
  // shows, or two rays would land on one pixel: its Jacobian stays positive
  // on a polar grid over that disc.
  for (int i = 1; i <= 200; ++i)
    for (int a = 0; a < 360; ++a) {
      const double r = max_r * i / 200.0, t = a * M_PI / 180.0;
      if (!(distortion_jacobian_det(lens, {r * std::cos(t), r * std::sin(t)}) > 0))
        fail(where, "the lens distortion (" + describe_lens(lens) +
                        ") folds the image: the mapping turns back " + std::to_string(r) +
                        " focal lengths from the centre, inside the frame");
    }
  LensMapping m;
  // The canvas keeps the finer of the two pixel pitches, so no output pixel
  // is magnified from it at the centre.
  const double fc = std::max(fx, fy);
  m.canvas = camera;
  m.canvas.f = fc;
  m.canvas.fy = 0.0;
  m.canvas.cx = -fc * x0 + kCanvasPad;
  m.canvas.cy = -fc * y0 + kCanvasPad;
  const double cw = std::ceil(fc * (x1 - x0)) + 2 * kCanvasPad + 1;
  const double ch = std::ceil(fc * (y1 - y0)) + 2 * kCanvasPad + 1;
  if (!(cw <= kMaxImageSide && ch <= kMaxImageSide))
    fail(where, "the lens distortion and focal lengths need a " + std::to_string(cw) + "x" +
                    std::to_string(ch) + " render to cover the image, more than " +
                    std::to_string(kMaxImageSide) + " px a side");
  m.canvas.width = static_cast<int>(cw);
  m.canvas.height = static_cast<int>(ch);
  m.map_x.create(h, w, CV_32F);
  m.map_y.create(h, w, CV_32F);
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const Eigen::Vector2d& xy = rays[static_cast<size_t>(v) * w + u];
      m.map_x.at<float>(v, u) = static_cast<float>(fc * xy.x() + m.canvas.cx);
      m.map_y.at<float>(v, u) = static_cast<float>(fc * xy.y() + m.canvas.cy);
    }
  return m;
}

void apply_lens_colour(const LensMapping& mapping, const cv::Mat& canvas_bgr, cv::Mat& out) {
  cv::remap(canvas_bgr, out, mapping.map_x, mapping.map_y, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
}

void apply_lens(const LensMapping& mapping, const RenderedFrame& canvas, RenderedFrame& out) {
  if (!canvas.bgr.empty()) apply_lens_colour(mapping, canvas.bgr, out.bgr);
  // Depth and labels from one canvas pixel each, never mixed across an edge.
  if (!canvas.depth.empty())
    cv::remap(canvas.depth, out.depth, mapping.map_x, mapping.map_y, cv::INTER_NEAREST,
              cv::BORDER_REPLICATE);
  if (!canvas.instance.empty())
    cv::remap(canvas.instance, out.instance, mapping.map_x, mapping.map_y, cv::INTER_NEAREST,
              cv::BORDER_REPLICATE);
}

}  // namespace depot::sim
