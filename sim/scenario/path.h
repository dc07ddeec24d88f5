#pragma once
// A ground path for actors and robot cameras: waypoints with rounded corners
// (Chaikin corner cutting), sampled by arc length so motion is smooth.
// An open path is walked out and back (a narrow loop, so turns stay smooth).
#include <vector>

#include <Eigen/Core>

namespace depot::sim {

// A smooth sideways shift of a path within its lane (m, positive = left of the
// direction of travel) as a function of arc length s on the unshifted path of
// length L: constant + amplitude * sin(2 pi cycles s / L + phase). Whole
// cycles keep a closed path closed; |constant| + |amplitude| bounds the shift.
struct LaneOffset {
  double constant = 0.0;
  double amplitude = 0.0;
  int cycles = 1;
  double phase = 0.0;
  double at(double s, double length) const;
  double bound() const;
  bool none() const { return constant == 0.0 && amplitude == 0.0; }
};

class Path2D {
 public:
  Path2D() = default;
  // `closed`: the last waypoint connects back to the first.
  // `lane` shifts the smoothed path sideways (see LaneOffset).
  Path2D(const std::vector<Eigen::Vector2d>& waypoints, bool closed, double corner_radius = 0.5,
         const LaneOffset& lane = {});

  double length() const { return cumulative_.empty() ? 0.0 : cumulative_.back(); }
  // Position and unit tangent at arc length s (wraps around: paths repeat).
  Eigen::Vector2d position(double s) const;
  Eigen::Vector2d tangent(double s) const;
  double heading(double s) const;  // rad, atan2 of the tangent
  // The dense polyline the path follows (closed: last == first).
  const std::vector<Eigen::Vector2d>& points() const { return points_; }

 private:
  double wrap(double s) const;
  size_t segment(double s) const;
  std::vector<Eigen::Vector2d> points_;  // dense, closed (last == first)
  std::vector<double> cumulative_;
};

}  // namespace depot::sim
