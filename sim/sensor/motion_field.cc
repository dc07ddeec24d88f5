#include "sim/sensor/motion_field.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "common/error.h"

namespace depot::sim {

namespace {

constexpr float kNearest = 0.01f;  // m, points nearer the moved camera are dropped
// How far (pixels) an unreached pixel looks for a reached one in each
// direction: a band along the border is as wide as the image motion, but
// may run the image's whole height.
constexpr int kFillReach = 96;
constexpr int16_t kAtInfinity = -1;

}  // namespace

InstantMotion instant_motion(const Pose& camera_at_stamp, const std::vector<Pose>& bodies_at_stamp,
                             const Pose& camera, const std::vector<Pose>& bodies) {
  if (bodies.size() != bodies_at_stamp.size())
    fail("motion field", "the bodies at the stamp and at the instant differ in number");
  InstantMotion m;
  const Pose camera_from_world = camera.inverse();
  m.scene = camera_from_world * camera_at_stamp;
  m.bodies.reserve(bodies.size());
  for (size_t b = 0; b < bodies.size(); ++b)
    m.bodies.push_back(camera_from_world * bodies[b] * bodies_at_stamp[b].inverse() *
                       camera_at_stamp);
  return m;
}

cv::Mat assign_bodies(const cv::Mat& depth, const cv::Mat& instance, const CameraIntrinsics& camera,
                      const std::vector<uint16_t>& body_instance,
                      const std::vector<Eigen::Vector3d>& body_origin) {
  if (depth.type() != CV_32F || instance.type() != CV_16U || depth.size() != instance.size())
    fail("motion field", "depth and instance images differ in size or type");
  if (body_instance.size() != body_origin.size())
    fail("motion field", "bodies and their origins differ in number");
  if (body_instance.size() > static_cast<size_t>(INT16_MAX))
    fail("motion field", "more bodies than a body map holds (32767)");
  // The bodies of each instance id.
  uint16_t largest = 0;
  for (uint16_t id : body_instance) largest = std::max(largest, id);
  std::vector<std::vector<int>> of_instance(largest + 1);
  for (size_t b = 0; b < body_instance.size(); ++b)
    if (body_instance[b] > 0) of_instance[body_instance[b]].push_back(static_cast<int>(b));
  cv::Mat body(depth.size(), CV_16S, cv::Scalar(-1));
  for (int y = 0; y < depth.rows; ++y) {
    const float* d = depth.ptr<float>(y);
    const uint16_t* id = instance.ptr<uint16_t>(y);
    int16_t* out = body.ptr<int16_t>(y);
    for (int x = 0; x < depth.cols; ++x) {
      if (d[x] <= 0 || id[x] > largest || of_instance[id[x]].empty()) continue;
      const Eigen::Vector3d p(d[x] * (x - camera.cx) / camera.f, d[x] * (y - camera.cy) / camera.f,
                              d[x]);
      double best = std::numeric_limits<double>::infinity();
      for (int b : of_instance[id[x]]) {
        const double distance = (body_origin[b] - p).squaredNorm();
        if (distance < best) best = distance, out[x] = static_cast<int16_t>(b);
      }
    }
  }
  return body;
}

FieldSource make_field_source(const cv::Mat& bgr, const cv::Mat& depth, const cv::Mat& body,
                              const CameraIntrinsics& camera) {
  if (bgr.type() != CV_8UC3 || depth.type() != CV_32F || body.type() != CV_16S ||
      bgr.size() != depth.size() || bgr.size() != body.size())
    fail("motion field", "colour, depth and body images differ in size or type");
  FieldSource s;
  s.bgr = bgr.isContinuous() ? bgr : bgr.clone();
  s.f = static_cast<float>(camera.f);
  s.cx = static_cast<float>(camera.cx);
  s.cy = static_cast<float>(camera.cy);
  const int w = bgr.cols, h = bgr.rows;
  s.points.resize(static_cast<size_t>(w) * h);
  s.motion.resize(s.points.size());
  for (int y = 0, i = 0; y < h; ++y) {
    const float* d = depth.ptr<float>(y);
    const int16_t* b = body.ptr<int16_t>(y);
    for (int x = 0; x < w; ++x, ++i) {
      const Eigen::Vector3f ray((x - s.cx) / s.f, (y - s.cy) / s.f, 1.0f);
      if (d[x] <= 0) {
        s.points[i] = ray;  // a direction: at infinity only the rotation moves it
        s.motion[i] = kAtInfinity;
      } else {
        s.points[i] = d[x] * ray;
        s.motion[i] = static_cast<int16_t>(b[x] + 1);
        s.bodies = std::max(s.bodies, b[x] + 1);
      }
    }
  }
  return s;
}

void synthesise_subframe(const FieldSource& source, const InstantMotion& motion, cv::Mat& out) {
  const int w = source.bgr.cols, h = source.bgr.rows, n = w * h;
  if (static_cast<int>(motion.bodies.size()) < source.bodies)
    fail("motion field", "a pixel follows a body that has no motion");
  const float f = source.f, cx = source.cx, cy = source.cy;
  // The motions as float 3x4: [0] the static scene, [1 + b] body b.
  std::vector<Eigen::Matrix<float, 3, 4>> motions;
  motions.push_back(motion.scene.matrix().topRows<3>().cast<float>());
  for (const Pose& m : motion.bodies) motions.push_back(m.matrix().topRows<3>().cast<float>());
  // A z-buffer of (depth, source pixel) in one key: positive floats order
  // as their bits do, so the smallest key is the nearest point, ties going
  // to the first pixel. Each point lands on the pixel nearest it, as the
  // renderer rasterises (no antialiasing): a bilinear splat would soften
  // every edge the re-rendered reference keeps sharp.
  constexpr uint64_t kEmpty = std::numeric_limits<uint64_t>::max();
  // Scratch kept per thread: fresh pages for every sub-frame cost more than
  // the splatting itself.
  thread_local std::vector<uint64_t> nearest;
  thread_local std::vector<int> holes;
  thread_local std::vector<std::pair<int, int>> fills;  // (hole, the pixel it copies)
  nearest.assign(n, kEmpty);
  holes.clear();
  fills.clear();
  const float far_bits = std::numeric_limits<float>::max();
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3f& p = source.points[i];
    const int16_t which = source.motion[i];
    Eigen::Vector3f q;
    float z;
    if (which == kAtInfinity) {
      q = motions[0].leftCols<3>() * p;
      if (q.z() <= 0) continue;
      z = far_bits;
    } else {
      const Eigen::Matrix<float, 3, 4>& m = motions[which];
      q = m.leftCols<3>() * p + m.col(3);
      if (q.z() < kNearest) continue;
      z = q.z();
    }
    const float inverse = 1.0f / q.z();
    const float u = f * q.x() * inverse + cx, v = f * q.y() * inverse + cy;
    if (!(u > -0.5f && v > -0.5f && u < w - 0.5f && v < h - 0.5f)) continue;
    const int t = std::min(h - 1, static_cast<int>(v + 0.5f)) * w +
                  std::min(w - 1, static_cast<int>(u + 0.5f));
    uint32_t bits;
    std::memcpy(&bits, &z, sizeof(bits));
    nearest[t] =
        std::min(nearest[t], (static_cast<uint64_t>(bits) << 32) | static_cast<uint32_t>(i));
  }
  if (!out.isContinuous()) out.release();  // a view into a larger image
  out.create(h, w, CV_8UC3);
  out.setTo(cv::Scalar::all(0));
  const uchar* in = source.bgr.ptr<uchar>(0);
  uchar* o = out.ptr<uchar>(0);
  for (int t = 0; t < n; ++t) {
    if (nearest[t] == kEmpty) {
      holes.push_back(t);
      continue;
    }
    const uint32_t i = static_cast<uint32_t>(nearest[t]);
    o[3 * t] = in[3 * i];
    o[3 * t + 1] = in[3 * i + 1];
    o[3 * t + 2] = in[3 * i + 2];
  }
  // An unreached pixel takes the colour of the farthest of the nearest
  // reached pixels left, right, above and below it: what an actor uncovers
  // is the background beside it, not the actor itself.
  for (int t : holes) {
    const int x = t % w, y = t / w;
    int from = -1, from_distance = 0;
    auto consider = [&](int j, int distance) {
      const uint64_t depth = nearest[j] >> 32;
      if (from < 0 || depth > (nearest[from] >> 32) ||
          (depth == (nearest[from] >> 32) && distance < from_distance))
        from = j, from_distance = distance;
    };
    // The first reached pixel `step` apart, at most kFillReach steps away.
    auto look = [&](int step, int steps) {
      for (int k = 1, j = t + step; k <= std::min(steps, kFillReach); ++k, j += step)
        if (nearest[j] != kEmpty) {
          consider(j, k);
          return;
        }
    };
    look(-1, x);
    look(1, w - 1 - x);
    look(-w, y);
    look(w, h - 1 - y);
    if (from >= 0) fills.emplace_back(t, from);  // none near: stays black
  }
  for (const auto& [t, from] : fills)
    for (int ch = 0; ch < 3; ++ch) o[3 * t + ch] = o[3 * from + ch];
}

}  // namespace depot::sim
