#include "tests/support/synthetic_room.h"

#include <algorithm>
#include <cmath>

namespace depot::test {
namespace {

// A uniform number in [0, 1) for the integer tuple (splitmix64 mixing).
double hash01(uint64_t seed, int64_t a, int64_t b, int64_t c) {
  uint64_t x = seed * 0x9E3779B97F4A7C15ull ^ static_cast<uint64_t>(a) * 0xBF58476D1CE4E5B9ull ^
               static_cast<uint64_t>(b) * 0x94D049BB133111EBull ^
               static_cast<uint64_t>(c) * 0xD6E8FEB86659FD93ull;
  x ^= x >> 30;
  x *= 0xBF58476D1CE4E5B9ull;
  x ^= x >> 27;
  x *= 0x94D049BB133111EBull;
  x ^= x >> 31;
  return static_cast<double>(x >> 11) * (1.0 / 9007199254740992.0);
}

// Smooth random variation (value noise): random levels in [-1, 1] on a
// lattice of `spacing` metres, bilinearly interpolated.
double value_noise(uint64_t seed, int face, double a, double b, double spacing, int octave) {
  const double x = a / spacing, y = b / spacing;
  const double fx = std::floor(x), fy = std::floor(y);
  const int64_t ix = static_cast<int64_t>(fx), iy = static_cast<int64_t>(fy);
  const double wx = x - fx, wy = y - fy;
  auto at = [&](int64_t i, int64_t j) {
    return 2.0 * hash01(seed, face * 16 + octave, i * 1000003 + j, 6) - 1.0;
  };
  return (1 - wy) * ((1 - wx) * at(ix, iy) + wx * at(ix + 1, iy)) +
         wy * ((1 - wx) * at(ix, iy + 1) + wx * at(ix + 1, iy + 1));
}

// Grey level (0-255) of face `face` at surface coordinates (a, b) in metres:
// panels and blocks give corners, the value noise over them makes every
// corner's neighbourhood its own (no two descriptors alike).
double texture(uint64_t seed, int face, double a, double b) {
  const double panel = 0.32, block = 0.075;
  const int64_t row = static_cast<int64_t>(std::floor(b / panel));
  const double shift = hash01(seed, face, row, 1) * panel;  // rows offset like bricks
  const int64_t col = static_cast<int64_t>(std::floor((a + shift) / panel));
  double level = 35.0 + 185.0 * hash01(seed, face * 1000 + row, col, 2);
  if (hash01(seed, face * 1000 + row, col, 3) < 0.55) {  // a panel with finer blocks
    const int64_t row2 = static_cast<int64_t>(std::floor(b / block));
    const double shift2 = hash01(seed, face, row2, 4) * block;
    const int64_t col2 = static_cast<int64_t>(std::floor((a + shift2) / block));
    level += (hash01(seed, face * 1000 + row2, col2, 5) - 0.5) * 110.0;
  }
  level +=
      30.0 * value_noise(seed, face, a, b, 0.02, 0) + 25.0 * value_noise(seed, face, a, b, 0.05, 1);
  return std::clamp(level, 0.0, 255.0);
}

// Where the ray o + t d (o inside the room) leaves it: t, and the face hit
// (0..5: -x +x -y +y -z +z; the boxes' faces follow) with its surface
// coordinates.
struct Hit {
  double t = 0;
  int face = 0;
  double a = 0, b = 0;
};

Hit cast(const Eigen::Vector3d& half, const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  Hit hit;
  hit.t = INFINITY;
  for (int axis = 0; axis < 3; ++axis) {
    if (std::abs(d[axis]) < 1e-12) continue;
    const int side = d[axis] > 0 ? 1 : 0;
    const double t = ((side ? half[axis] : -half[axis]) - o[axis]) / d[axis];
    if (t > 0 && t < hit.t) {
      hit.t = t;
      hit.face = 2 * axis + side;
    }
  }
  return hit;
}

// The nearest entry of the ray into box `b` (the slab method) when it is
// nearer than `hit`, as face 6 + 6 k + (2 axis + side) of the k-th box.
void cast_box(const RoomBox& b, int k, const Eigen::Vector3d& o, const Eigen::Vector3d& d,
              Hit& hit) {
  double enter = -INFINITY, leave = INFINITY;
  int enter_face = 0;
  for (int axis = 0; axis < 3; ++axis) {
    const double lo = b.centre[axis] - b.half_size[axis], hi = b.centre[axis] + b.half_size[axis];
    if (std::abs(d[axis]) < 1e-12) {
      if (o[axis] < lo || o[axis] > hi) return;
      continue;
    }
    double t0 = (lo - o[axis]) / d[axis], t1 = (hi - o[axis]) / d[axis];
    int face = 2 * axis;  // entering through the low side
    if (t0 > t1) {
      std::swap(t0, t1);
      face = 2 * axis + 1;
    }
    if (t0 > enter) {
      enter = t0;
      enter_face = face;
    }
    leave = std::min(leave, t1);
  }
  if (enter > 0 && enter <= leave && enter < hit.t) {
    hit.t = enter;
    hit.face = 6 + 6 * k + enter_face;
  }
}

Hit cast_scene(const SyntheticRoom& room, const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  Hit hit = cast(room.half_size, o, d);
  for (size_t k = 0; k < room.boxes.size(); ++k)
    cast_box(room.boxes[k], static_cast<int>(k), o, d, hit);
  const Eigen::Vector3d p = o + hit.t * d;
  const int axis = (hit.face % 6) / 2;
  hit.a = p[(axis + 1) % 3];
  hit.b = p[(axis + 2) % 3];
  return hit;
}

}  // namespace

RealFrame render_room(const SyntheticRoom& room, const slam::PinholeCamera& camera,
                      const Pose& T_cw) {
  const Pose T_wc = T_cw.inverse();
  const Eigen::Matrix3d R = T_wc.linear();
  const Eigen::Vector3d o = T_wc.translation();
  RealFrame frame;
  frame.bgr.create(camera.height, camera.width, CV_8UC3);
  frame.depth.create(camera.height, camera.width, CV_32F);
  // A faint tint per face, so the colour image reads as a room.
  static const double kTint[6][3] = {{1.0, 0.95, 0.9}, {0.9, 0.95, 1.0},  {0.95, 1.0, 0.95},
                                     {1.0, 1.0, 1.0},  {1.0, 0.92, 0.92}, {0.92, 0.92, 1.0}};
  for (int v = 0; v < camera.height; ++v)
    for (int u = 0; u < camera.width; ++u) {
      // Depth: the pixel centre's ray; its camera z is t (the ray has z = 1).
      const Hit centre = cast_scene(room, o, R * camera.unproject(u, v, 1.0));
      frame.depth.at<float>(v, u) = static_cast<float>(centre.t);
      double tint[3] = {0, 0, 0};
      for (int s = 0; s < 4; ++s) {
        const double du = (s % 2) * 0.5 - 0.25, dv = (s / 2) * 0.5 - 0.25;
        const Hit h = cast_scene(room, o, R * camera.unproject(u + du, v + dv, 1.0));
        const double g = texture(room.seed, h.face, h.a, h.b);
        for (int c = 0; c < 3; ++c) tint[c] += g * kTint[h.face % 6][c] / 4;
      }
      cv::Vec3b& px = frame.bgr.at<cv::Vec3b>(v, u);
      for (int c = 0; c < 3; ++c) px[c] = cv::saturate_cast<uint8_t>(tint[c]);
    }
  return frame;
}

RealFrame room_frame() {
  return render_room(SyntheticRoom{}, slam::PinholeCamera{}, Pose::Identity());
}

RealFrame room_view(const Eigen::Matrix3d& rotation) {
  return render_room(SyntheticRoom{}, slam::PinholeCamera{}, turned_pose(rotation));
}

}  // namespace depot::test
