#pragma once
// A ground path for actors and robot cameras: waypoints with rounded corners
// (Chaikin corner cutting), sampled by arc length so motion is smooth.
// An open path is walked out and back (a narrow loop, so turns stay smooth).
#include <vector>

#include <Eigen/Core>

namespace depot::sim {

class Path2D {
 public:
  Path2D() = default;
  // `closed`: the last waypoint connects back to the first.
  Path2D(const std::vector<Eigen::Vector2d>& waypoints, bool closed, double corner_radius = 0.5);

  double length() const { return cumulative_.empty() ? 0.0 : cumulative_.back(); }
  // Position and unit tangent at arc length s (wraps around: paths repeat).
  Eigen::Vector2d position(double s) const;
  Eigen::Vector2d tangent(double s) const;
  double heading(double s) const;  // rad, atan2 of the tangent

 private:
  double wrap(double s) const;
  size_t segment(double s) const;
  std::vector<Eigen::Vector2d> points_;  // dense, closed (last == first)
  std::vector<double> cumulative_;
};

}  // namespace depot::sim
