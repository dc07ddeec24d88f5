#include "sim/sensor/motion_field.h"

#include <algorithm>
#include <array>
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
  const size_t n = static_cast<size_t>(w) * h;
  s.x.resize(n);
  s.y.resize(n);
  s.z.resize(n);
  s.w.resize(n);
  for (int y = 0, i = 0; y < h; ++y) {
    const float* d = depth.ptr<float>(y);
    const int16_t* b = body.ptr<int16_t>(y);
    for (int x = 0; x < w; ++x, ++i) {
      // A surface's point, or at infinity its direction.
      const float scale = d[x] <= 0 ? 1.0f : d[x];
      s.x[i] = scale * ((x - s.cx) / s.f);
      s.y[i] = scale * ((y - s.cy) / s.f);
      s.z[i] = scale;
      s.w[i] = d[x] <= 0 ? 0.0f : 1.0f;
      if (d[x] > 0 && b[x] >= 0) {
        s.on_body.push_back(i);
        s.body_of.push_back(b[x]);
        s.bodies = std::max(s.bodies, b[x] + 1);
      }
    }
  }
  return s;
}

namespace {

constexpr uint64_t kEmpty = std::numeric_limits<uint64_t>::max();
constexpr float kFar = std::numeric_limits<float>::max();
constexpr float kLeast = std::numeric_limits<float>::denorm_min();

// Where points land under float 3x4 motions: the nearest pixel, as the
// renderer rasterises (no antialiasing: a bilinear splat would soften every
// edge the re-rendered reference keeps sharp), or -1; and their depth there
// (kFar at infinity). Either pixels [begin, end) under motions[0], or
// (kListed) the source's pixels on bodies [begin, end) each under its
// body's motion; written at the pixel's index less `tile`, the first pixel
// of the tile the scratch holds. Branch-free on raw arrays so the compiler
// vectorises the
// pass over the whole image; the sums run in the order Eigen's product
// uses, so every point lands where Eigen would put it (datasets unchanged).
template <bool kListed>
void land_points(const FieldSource& s, const std::array<float, 12>* motions, int begin, int end,
                 int tile, int* __restrict target, float* __restrict depth) {
  const float* __restrict x = s.x.data();
  const float* __restrict y = s.y.data();
  const float* __restrict z = s.z.data();
  const float* __restrict hw = s.w.data();
  const int w = s.bgr.cols, h = s.bgr.rows;
  const float f = s.f, cx = s.cx, cy = s.cy, right = w - 0.5f, bottom = h - 0.5f;
  for (int k = begin; k < end; ++k) {
    // Listed: the k-th pixel on a body, with its body's motion; else pixel
    // k with the one motion.
    const int i = kListed ? s.on_body[k] : k;
    const float* m = motions[kListed ? s.body_of[k] : 0].data();
    const float m0 = m[0], m1 = m[1], m2 = m[2], m3 = m[3], m4 = m[4], m5 = m[5];
    const float m6 = m[6], m7 = m[7], m8 = m[8], m9 = m[9], m10 = m[10], m11 = m[11];
    const float qx = (m0 * x[i] + (m1 * y[i] + m2 * z[i])) + m3 * hw[i];
    const float qy = (m4 * x[i] + (m5 * y[i] + m6 * z[i])) + m7 * hw[i];
    const float qz = (m8 * x[i] + (m9 * y[i] + m10 * z[i])) + m11 * hw[i];
    // Points nearer the moved camera than kNearest are dropped; at
    // infinity (hw = 0), what turned behind it: qz > 0 is qz >= the least
    // float. Arithmetic on hw rather than branches keeps the loop one
    // vector path.
    const bool ahead = qz >= kNearest * hw[i] + kLeast * (1.0f - hw[i]);
    // Behind the camera u and v may be infinite or NaN: `ahead` drops them.
    const float inverse = 1.0f / qz;
    const float u = f * qx * inverse + cx, v = f * qy * inverse + cy;
    const bool inside = ahead & (u > -0.5f) & (v > -0.5f) & (u < right) & (v < bottom);
    // Clamped before the conversion, which is only defined in range.
    float uc = u > 0.0f ? u : 0.0f, vc = v > 0.0f ? v : 0.0f;
    uc = uc < w - 1 ? uc : w - 1;
    vc = vc < h - 1 ? vc : h - 1;
    const int column = static_cast<int>(uc + 0.5f), row = static_cast<int>(vc + 0.5f);
    target[i - tile] = inside ? row * w + column : -1;
    const float far = kFar * (1.0f - hw[i]);  // 0 for a surface
    depth[i - tile] = qz > far ? qz : far;
  }
}

// The row-major 3x4 of a pose, in float.
std::array<float, 12> motion_matrix(const Pose& pose) {
  std::array<float, 12> m;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) m[4 * r + c] = static_cast<float>(pose.matrix()(r, c));
  return m;
}

// Every unreached pixel (`holes`, ascending) takes the colour of the
// farthest of the nearest reached pixels left, right, above and below it,
// at most kFillReach away (ties: the nearer, then left, right, above,
// below): what an actor uncovers is the background beside it, not the
// actor itself. Each hole finds them in constant time (left and right from
// the run of holes it lies in, above and below from the hole next to it),
// so a band of holes along the border costs no more than a few.
void fill_holes(const std::vector<uint64_t>& nearest, const std::vector<int>& holes, int w, int h,
                uchar* out) {
  if (holes.empty()) return;
  thread_local std::vector<int> from, from_distance;  // per hole: the pixel it copies
  from.assign(holes.size(), -1);
  from_distance.assign(holes.size(), 0);
  const auto consider = [&](size_t k, int j, int distance) {
    const uint64_t depth = nearest[j] >> 32;
    if (from[k] < 0 || depth > (nearest[from[k]] >> 32) ||
        (depth == (nearest[from[k]] >> 32) && distance < from_distance[k]))
      from[k] = j, from_distance[k] = distance;
  };
  // Left and right: the run of holes a hole lies in ends where the nearest
  // reached pixels are.
  for (size_t k = 0; k < holes.size();) {
    const int row = holes[k] / w;
    size_t end = k + 1;  // the run: holes[k .. end) are consecutive in one row
    while (end < holes.size() && holes[end] == holes[end - 1] + 1 && holes[end] / w == row) ++end;
    const int left = holes[k] - 1, right = holes[end - 1] + 1;
    const bool has_left = holes[k] % w > 0, has_right = holes[end - 1] % w < w - 1;
    for (size_t q = k; q < end; ++q) {
      const int t = holes[q];
      if (has_left && t - left <= kFillReach) consider(q, left, t - left);
      if (has_right && right - t <= kFillReach) consider(q, right, right - t);
    }
    k = end;
  }
  // Above, then below: holes in order, each column remembering its last
  // hole's row and the reached row that hole saw. A hole whose neighbour
  // (above, or below) is a hole sees what that hole saw; any other
  // neighbour is reached.
  thread_local std::vector<int> hole_row, seen_row;  // per column
  const auto vertical = [&](bool above) {
    hole_row.assign(w, -2);
    seen_row.assign(w, -1);
    const int step = above ? -1 : 1;
    for (size_t q = 0; q < holes.size(); ++q) {
      const size_t k = above ? q : holes.size() - 1 - q;
      const int x = holes[k] % w, y = holes[k] / w, next = y + step;
      if (next < 0 || next >= h) {
        hole_row[x] = y, seen_row[x] = -1;
        continue;
      }
      const int seen = hole_row[x] == next ? seen_row[x] : next;
      hole_row[x] = y, seen_row[x] = seen;
      const int distance = std::abs(y - seen);
      if (seen >= 0 && distance <= kFillReach) consider(k, seen * w + x, distance);
    }
  };
  vertical(true);
  vertical(false);
  // Choose from the reached pixels only: copied after every choice is made.
  for (size_t k = 0; k < holes.size(); ++k)
    if (from[k] >= 0)  // none near: stays black
      for (int ch = 0; ch < 3; ++ch) out[3 * holes[k] + ch] = out[3 * from[k] + ch];
}

}  // namespace

void synthesise_subframe(const FieldSource& source, const InstantMotion& motion, cv::Mat& out) {
  const int w = source.bgr.cols, h = source.bgr.rows, n = w * h;
  if (static_cast<int>(motion.bodies.size()) < source.bodies)
    fail("motion field", "a pixel follows a body that has no motion");
  // The points are landed and splatted a tile of rows at a time, so their
  // landing places stay in cache between the two passes.
  constexpr int kTileRows = 16;
  const int tile_size = kTileRows * w;
  thread_local std::vector<int> target;   // per point of a tile, the pixel it lands on (-1: none)
  thread_local std::vector<float> depth;  // its depth there
  target.resize(tile_size);
  depth.resize(tile_size);
  const std::array<float, 12> scene = motion_matrix(motion.scene);
  std::vector<std::array<float, 12>> bodies;
  for (const Pose& m : motion.bodies) bodies.push_back(motion_matrix(m));
  // A z-buffer of (depth, source pixel) in one key: positive floats order
  // as their bits do, so the smallest key is the nearest point, ties going
  // to the first pixel. Scratch kept per thread: fresh pages for every
  // sub-frame cost more than the splatting itself.
  thread_local std::vector<uint64_t> nearest;
  nearest.assign(n, kEmpty);
  const int listed = static_cast<int>(source.on_body.size());
  for (int begin = 0, body = 0; begin < n; begin += tile_size) {
    const int end = std::min(n, begin + tile_size);
    // The static scene (and the sky) over every pixel, then the few on
    // bodies again with their own motion.
    land_points<false>(source, &scene, begin, end, begin, target.data(), depth.data());
    const int first_body = body;
    while (body < listed && source.on_body[body] < end) ++body;
    land_points<true>(source, bodies.data(), first_body, body, begin, target.data(), depth.data());
    for (int i = begin; i < end; ++i) {
      const int t = target[i - begin];
      if (t < 0) continue;
      uint32_t bits;
      std::memcpy(&bits, &depth[i - begin], sizeof(bits));
      nearest[t] =
          std::min(nearest[t], (static_cast<uint64_t>(bits) << 32) | static_cast<uint32_t>(i));
    }
  }
  if (!out.isContinuous()) out.release();  // a view into a larger image
  out.create(h, w, CV_8UC3);
  const uchar* in = source.bgr.ptr<uchar>(0);
  uchar* o = out.ptr<uchar>(0);
  thread_local std::vector<int> holes;
  holes.clear();
  for (int t = 0; t < n; ++t) {
    const uint32_t i = static_cast<uint32_t>(nearest[t]);
    if (nearest[t] == kEmpty) {
      holes.push_back(t);
      o[3 * t] = o[3 * t + 1] = o[3 * t + 2] = 0;
      continue;
    }
    o[3 * t] = in[3 * i];
    o[3 * t + 1] = in[3 * i + 1];
    o[3 * t + 2] = in[3 * i + 2];
  }
  fill_holes(nearest, holes, w, h, o);
}

}  // namespace depot::sim
