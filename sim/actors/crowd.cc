#include "sim/actors/crowd.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "common/rng.h"

namespace depot::sim {
namespace {

constexpr double kBodyTop = 1.9;          // m: walkers are checked against geometry up to here
constexpr double kRelaxation = 0.5;       // s, to reach the wanted velocity
constexpr double kWalkerRange = 2.0;      // m, walkers further apart ignore each other
constexpr double kWalkerPush = 3.0;       // m/s^2 at contact distance
constexpr double kWalkerFalloff = 0.35;   // m
constexpr double kGeometryRange = 1.0;    // m
constexpr double kGeometryPush = 4.0;     // m/s^2 at the clearance
constexpr double kGeometryFalloff = 0.2;  // m
constexpr double kTurnRate = 4.0;         // rad/s
constexpr double kGoalReached = 0.5;      // m
constexpr double kEndStrip = 1.0;         // m, the goal strip at each end ("ends")

struct Walker {
  Eigen::Vector2d p{0, 0}, v{0, 0}, goal{0, 0};
  double speed = 1.0, heading = 0.0, walked = 0.0;
  int end = 0;  // "ends": the end it heads for
  Rng rng{1};
  std::vector<TrackPoint> track;
};

double wrap_angle(double a) {
  return std::atan2(std::sin(a), std::cos(a));
}

Eigen::Vector2d clearance_gradient(const ColumnClearance& clearance, const Eigen::Vector2d& p) {
  const double e = 0.05;
  const Eigen::Vector2d dx(e, 0), dy(0, e);
  Eigen::Vector2d g((clearance(p + dx, 0, kBodyTop) - clearance(p - dx, 0, kBodyTop)) / (2 * e),
                    (clearance(p + dy, 0, kBodyTop) - clearance(p - dy, 0, kBodyTop)) / (2 * e));
  const double n = g.norm();
  return n > 1e-9 ? Eigen::Vector2d(g / n) : Eigen::Vector2d(0, 0);
}

// A goal for a walker of crowd c: a point in the strip at its next end, or
// anywhere in the area; clear of static geometry.
Eigen::Vector2d draw_goal(const CrowdSpec& c, Walker& w, const ColumnClearance& clearance) {
  const Eigen::Vector2d size = c.hi - c.lo;
  const int long_axis = size.x() >= size.y() ? 0 : 1;
  for (int attempt = 0; attempt < 50; ++attempt) {
    Eigen::Vector2d g(w.rng.uniform(c.lo.x(), c.hi.x()), w.rng.uniform(c.lo.y(), c.hi.y()));
    if (c.goals == "ends") {
      const double strip = std::min(kEndStrip, 0.5 * size[long_axis]);
      g[long_axis] = w.end == 0 ? c.lo[long_axis] + w.rng.uniform(0, strip)
                                : c.hi[long_axis] - w.rng.uniform(0, strip);
    }
    if (clearance(g, 0, kBodyTop) > kCrowdClearance + 0.1) return g;
  }
  return w.p;  // nowhere clear: stay (the area was checked at the start)
}

}  // namespace

TrackPoint track_at(const std::vector<TrackPoint>& track, double t) {
  if (track.empty()) return {};
  if (t <= track.front().t) return track.front();
  if (t >= track.back().t) return track.back();
  const double step = (track.back().t - track.front().t) / (track.size() - 1);
  const size_t i = std::min(track.size() - 2, static_cast<size_t>((t - track.front().t) / step));
  const TrackPoint& a = track[i];
  const TrackPoint& b = track[i + 1];
  const double u = std::clamp((t - a.t) / (b.t - a.t), 0.0, 1.0);
  TrackPoint out;
  out.t = t;
  out.xy = a.xy + u * (b.xy - a.xy);
  out.heading = a.heading + u * wrap_angle(b.heading - a.heading);
  out.walked = a.walked + u * (b.walked - a.walked);
  return out;
}

std::vector<ActorSpec> simulate_crowds(const std::vector<CrowdSpec>& crowds, double load,
                                       double duration, uint64_t world_seed,
                                       const ColumnClearance& clearance) {
  std::vector<Walker> walkers;
  std::vector<size_t> crowd_of;
  std::vector<std::string> names;
  for (size_t ci = 0; ci < crowds.size(); ++ci) {
    const CrowdSpec& c = crowds[ci];
    const int count = static_cast<int>(std::lround(c.count * load));
    // Starts: places on a grid a little wider than the spacing, clear of
    // static geometry and of earlier crowds, taken in a seeded order.
    Rng order(derive_seed(world_seed, name_hash(c.name), 0x7374617274));
    const double pitch = kCrowdSpacing + 0.15;
    std::vector<Eigen::Vector2d> places;
    for (double y = c.lo.y() + 0.5 * pitch; y <= c.hi.y(); y += pitch)
      for (double x = c.lo.x() + 0.5 * pitch; x <= c.hi.x(); x += pitch) {
        const Eigen::Vector2d p(x + order.uniform(-0.05, 0.05), y + order.uniform(-0.05, 0.05));
        const bool clear = clearance(p, 0, kBodyTop) > kCrowdClearance + 0.05 &&
                           std::all_of(walkers.begin(), walkers.end(), [&](const Walker& o) {
                             return (o.p - p).norm() > kCrowdSpacing + 0.1;
                           });
        if (clear) places.push_back(p);
      }
    if (static_cast<int>(places.size()) < count)
      fail(c.where, fmt::format("crowd '{}': its area holds {} walkers {:.2f} m apart and {:.2f} m "
                                "from static geometry, not {} (count x dynamic load)",
                                c.name, places.size(), kCrowdSpacing, kCrowdClearance, count));
    for (size_t i = places.size(); i > 1; --i) std::swap(places[i - 1], places[order.below(i)]);
    for (int k = 0; k < count; ++k) {
      Walker w;
      const std::string name = c.name + "_" + std::to_string(k + 1);
      w.rng = Rng(derive_seed(world_seed, name_hash(name), 0x63726f7764));
      w.speed = w.rng.uniform(c.speed_lo, c.speed_hi);
      w.end = static_cast<int>(w.rng.below(2));
      w.p = places[k];
      w.goal = draw_goal(c, w, clearance);
      const Eigen::Vector2d to_goal = w.goal - w.p;
      w.heading = to_goal.norm() > 1e-6 ? std::atan2(to_goal.y(), to_goal.x()) : 0.0;
      walkers.push_back(std::move(w));
      crowd_of.push_back(ci);
      names.push_back(name);
    }
  }
  const int steps = static_cast<int>(std::ceil(duration / kCrowdStep));
  auto record = [&](double t) {
    for (Walker& w : walkers) w.track.push_back({t, w.p, w.heading, w.walked});
  };
  record(0.0);
  std::vector<Eigen::Vector2d> acceleration(walkers.size());
  for (int step = 1; step <= steps && !walkers.empty(); ++step) {
    for (size_t i = 0; i < walkers.size(); ++i) {
      Walker& w = walkers[i];
      const CrowdSpec& c = crowds[crowd_of[i]];
      if ((w.goal - w.p).norm() < kGoalReached) {
        w.end = 1 - w.end;
        w.goal = draw_goal(c, w, clearance);
      }
      const Eigen::Vector2d to_goal = w.goal - w.p;
      const Eigen::Vector2d wanted = to_goal.norm() > 1e-6
                                         ? Eigen::Vector2d(w.speed * to_goal.normalized())
                                         : Eigen::Vector2d(0, 0);
      Eigen::Vector2d a = (wanted - w.v) / kRelaxation;
      for (size_t j = 0; j < walkers.size(); ++j) {
        if (j == i) continue;
        const Eigen::Vector2d d = w.p - walkers[j].p;
        const double dist = d.norm();
        if (dist > kWalkerRange || dist < 1e-9) continue;
        a += kWalkerPush * std::exp((kCrowdSpacing - dist) / kWalkerFalloff) * d / dist;
      }
      const double free = clearance(w.p, 0, kBodyTop);
      if (free < kGeometryRange)
        a += kGeometryPush * std::exp((kCrowdClearance - free) / kGeometryFalloff) *
             clearance_gradient(clearance, w.p);
      acceleration[i] = a;
    }
    for (size_t i = 0; i < walkers.size(); ++i) {
      Walker& w = walkers[i];
      w.v += kCrowdStep * acceleration[i];
      const double top = 1.3 * w.speed;
      if (w.v.norm() > top) w.v *= top / w.v.norm();
      w.p += kCrowdStep * w.v;
    }
    // Constraints: nobody inside another or inside the static scene.
    // (A little beyond the spacing, so the poses between samples keep it too.)
    const double spacing = kCrowdSpacing + 0.02, margin = kCrowdClearance + 0.01;
    for (int pass = 0; pass < 6; ++pass) {
      for (size_t i = 0; i < walkers.size(); ++i)
        for (size_t j = i + 1; j < walkers.size(); ++j) {
          Eigen::Vector2d d = walkers[i].p - walkers[j].p;
          const double dist = d.norm();
          if (dist >= spacing) continue;
          const Eigen::Vector2d n = dist > 1e-9 ? Eigen::Vector2d(d / dist) : Eigen::Vector2d(1, 0);
          const double push = 0.5 * (spacing - dist) + 1e-4;
          walkers[i].p += push * n;
          walkers[j].p -= push * n;
        }
      for (Walker& w : walkers) {
        const double free = clearance(w.p, 0, kBodyTop);
        if (free < margin) w.p += (margin - free + 1e-3) * clearance_gradient(clearance, w.p);
      }
    }
    for (size_t i = 0; i < walkers.size(); ++i) {
      Walker& w = walkers[i];
      const Eigen::Vector2d moved = w.p - w.track.back().xy;
      w.walked += moved.norm();
      if (w.v.norm() > 0.15) {
        const double turn = wrap_angle(std::atan2(w.v.y(), w.v.x()) - w.heading);
        const double most = kTurnRate * kCrowdStep;
        w.heading = wrap_angle(w.heading + std::clamp(turn, -most, most));
      }
    }
    record(step * kCrowdStep);
  }

  std::vector<ActorSpec> out;
  for (size_t i = 0; i < walkers.size(); ++i) {
    ActorSpec a;
    a.name = names[i];
    a.type = "human";
    a.action = "crowd";
    a.speed = walkers[i].speed;
    a.appearance = derive_seed(world_seed, name_hash(a.name), 1);
    a.track = std::move(walkers[i].track);
    a.path = {a.track.front().xy, a.track.back().xy};  // for checks that read paths
    out.push_back(std::move(a));
  }
  return out;
}

}  // namespace depot::sim
