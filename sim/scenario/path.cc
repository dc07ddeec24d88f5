#include "sim/scenario/path.h"

#include <algorithm>
#include <cmath>

namespace depot::sim {
namespace {

// One Chaikin pass on a closed polygon: each edge is replaced by the points at
// 1/4 and 3/4, which rounds every corner; repeated passes converge to a
// quadratic B-spline.
std::vector<Eigen::Vector2d> chaikin(const std::vector<Eigen::Vector2d>& in) {
  std::vector<Eigen::Vector2d> out;
  out.reserve(in.size() * 2);
  for (size_t i = 0; i < in.size(); ++i) {
    const Eigen::Vector2d& a = in[i];
    const Eigen::Vector2d& b = in[(i + 1) % in.size()];
    out.push_back(0.75 * a + 0.25 * b);
    out.push_back(0.25 * a + 0.75 * b);
  }
  return out;
}

// Inserts points so no straight piece is longer than `step`, keeping corner
// cutting local to `radius` around each corner.
std::vector<Eigen::Vector2d> densify_corners(const std::vector<Eigen::Vector2d>& in,
                                             double radius) {
  std::vector<Eigen::Vector2d> out;
  for (size_t i = 0; i < in.size(); ++i) {
    const Eigen::Vector2d& a = in[i];
    const Eigen::Vector2d& b = in[(i + 1) % in.size()];
    double len = (b - a).norm();
    out.push_back(a);
    if (len > 2.0 * radius) {
      Eigen::Vector2d dir = (b - a) / len;
      out.push_back(a + dir * radius);
      out.push_back(b - dir * radius);
    }
  }
  return out;
}

// Arc lengths along a polyline.
std::vector<double> arc_lengths(const std::vector<Eigen::Vector2d>& points) {
  std::vector<double> out(points.size(), 0.0);
  for (size_t i = 1; i < points.size(); ++i)
    out[i] = out[i - 1] + (points[i] - points[i - 1]).norm();
  return out;
}

}  // namespace

double LaneOffset::at(double s, double length) const {
  if (none() || length <= 0.0) return constant;
  return constant + amplitude * std::sin(2.0 * M_PI * cycles * s / length + phase);
}

double LaneOffset::bound() const {
  return std::abs(constant) + std::abs(amplitude);
}

Path2D::Path2D(const std::vector<Eigen::Vector2d>& waypoints, bool closed, double corner_radius,
               const LaneOffset& lane) {
  std::vector<Eigen::Vector2d> loop = waypoints;
  if (!closed && waypoints.size() >= 2) {
    // Out and back with a 0.4 m sideways offset on the way back.
    Eigen::Vector2d d = (waypoints.back() - waypoints.front()).normalized();
    Eigen::Vector2d side(-d.y(), d.x());
    for (auto it = waypoints.rbegin(); it != waypoints.rend(); ++it)
      loop.push_back(*it + 0.4 * side);
  }
  if (loop.size() < 2) loop.push_back(loop.empty() ? Eigen::Vector2d::Zero() : loop[0]);
  std::vector<Eigen::Vector2d> pts = densify_corners(loop, corner_radius);
  for (int pass = 0; pass < 4; ++pass) pts = chaikin(pts);
  pts.push_back(pts.front());
  if (!lane.none() && pts.size() > 2) {
    // Shift each point along its left normal (the direction between its
    // neighbours on the closed loop) by the lane offset at its arc length.
    const std::vector<double> s = arc_lengths(pts);
    const size_t n = pts.size() - 1;  // distinct points
    std::vector<Eigen::Vector2d> shifted(pts.size());
    for (size_t i = 0; i < n; ++i) {
      Eigen::Vector2d d = pts[(i + 1) % n] - pts[(i + n - 1) % n];
      if (d.norm() < 1e-12) d = Eigen::Vector2d(1.0, 0.0);
      d.normalize();
      shifted[i] = pts[i] + lane.at(s[i], s.back()) * Eigen::Vector2d(-d.y(), d.x());
    }
    shifted[n] = shifted[0];
    pts = shifted;
  }
  points_ = pts;
  cumulative_ = arc_lengths(points_);
}

double Path2D::wrap(double s) const {
  double len = length();
  if (len <= 0.0) return 0.0;
  s = std::fmod(s, len);
  return s < 0 ? s + len : s;
}

size_t Path2D::segment(double s) const {
  auto it = std::upper_bound(cumulative_.begin(), cumulative_.end(), s);
  size_t i = static_cast<size_t>(it - cumulative_.begin());
  return std::clamp<size_t>(i == 0 ? 0 : i - 1, 0, points_.size() - 2);
}

Eigen::Vector2d Path2D::position(double s) const {
  if (points_.size() < 2) return points_.empty() ? Eigen::Vector2d::Zero() : points_[0];
  s = wrap(s);
  size_t i = segment(s);
  double seg = cumulative_[i + 1] - cumulative_[i];
  double u = seg > 0 ? (s - cumulative_[i]) / seg : 0.0;
  return (1.0 - u) * points_[i] + u * points_[i + 1];
}

Eigen::Vector2d Path2D::tangent(double s) const {
  // Central difference over a short window gives a smooth heading.
  const double h = 0.05;
  Eigen::Vector2d d = position(s + h) - position(s - h);
  double n = d.norm();
  return n > 1e-9 ? Eigen::Vector2d(d / n) : Eigen::Vector2d(1.0, 0.0);
}

double Path2D::heading(double s) const {
  Eigen::Vector2d t = tangent(s);
  return std::atan2(t.y(), t.x());
}

}  // namespace depot::sim
