#pragma once
// OpenCV's radial-tangential lens model (ORB-SLAM2 and TUM calibrations use
// it), one formula for the simulator, which makes distorted images, and the
// SLAM, which undoes the distortion. On normalised coordinates (x, y) =
// (X/Z, Y/Z):
//   r2 = x^2 + y^2, radial = 1 + k1 r2 + k2 r2^2 + k3 r2^3
//   xd = x radial + 2 p1 x y + p2 (r2 + 2 x^2)
//   yd = y radial + p1 (r2 + 2 y^2) + 2 p2 x y
#include <string>

#include <Eigen/Core>

#include "common/number_text.h"

namespace depot {

struct LensCoefficients {
  double k1 = 0, k2 = 0, p1 = 0, p2 = 0, k3 = 0;
  bool any() const { return k1 != 0 || k2 != 0 || p1 != 0 || p2 != 0 || k3 != 0; }
};

// "k1 -0.25, k2 0.08, p1 0, p2 0, k3 0", as errors name a lens.
inline std::string describe_lens(const LensCoefficients& l) {
  return "k1 " + shortest_number(l.k1) + ", k2 " + shortest_number(l.k2) + ", p1 " +
         shortest_number(l.p1) + ", p2 " + shortest_number(l.p2) + ", k3 " + shortest_number(l.k3);
}

// The distorted normalised coordinates of the ray (x, y, 1).
inline Eigen::Vector2d distort_normalised(const LensCoefficients& l, const Eigen::Vector2d& xy) {
  const double x = xy.x(), y = xy.y(), r2 = x * x + y * y;
  const double radial = 1 + r2 * (l.k1 + r2 * (l.k2 + r2 * l.k3));
  return {x * radial + 2 * l.p1 * x * y + l.p2 * (r2 + 2 * x * x),
          y * radial + l.p1 * (r2 + 2 * y * y) + 2 * l.p2 * x * y};
}

}  // namespace depot
