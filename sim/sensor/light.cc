#include "sim/sensor/light.h"

#include <algorithm>
#include <cmath>

namespace depot::sim {

namespace {

// The events' level (without `level` or flicker) at t.
double event_level_at(const std::vector<Eigen::Vector2d>& events, double t) {
  if (events.empty()) return 1.0;
  if (t < events.front().x()) return events.front().y();
  // The last point at or before t: a switch (two points at one time) takes
  // the later point's level from its time on.
  size_t i = 0;
  while (i + 1 < events.size() && events[i + 1].x() <= t) ++i;
  if (i + 1 == events.size()) return events.back().y();
  const Eigen::Vector2d& a = events[i];
  const Eigen::Vector2d& b = events[i + 1];
  return a.y() + (b.y() - a.y()) * (t - a.x()) / (b.x() - a.x());
}

// Integral over [t0, t1] of (p + q t) (1 + A cos(w t)), in closed form.
double integral_linear_times_flicker(double p, double q, double amplitude, double w, double t0,
                                     double t1) {
  const double plain = p * (t1 - t0) + 0.5 * q * (t1 * t1 - t0 * t0);
  if (amplitude == 0.0 || w == 0.0) return plain;
  // d/dt [(p + q t) sin(w t) / w + q cos(w t) / w^2] = (p + q t) cos(w t)
  auto primitive = [&](double t) {
    return (p + q * t) * std::sin(w * t) / w + q * std::cos(w * t) / (w * w);
  };
  return plain + amplitude * (primitive(t1) - primitive(t0));
}

}  // namespace

double light_level_at(const LightSpec& light, double t) {
  const double w = 4.0 * M_PI * light.mains_hz;
  return light.level * event_level_at(light.events, t) * (1.0 + light.flicker * std::cos(w * t));
}

double mean_light_level(const LightSpec& light, double t0, double t1) {
  if (t1 <= t0) return light_level_at(light, t0);
  const double w = 4.0 * M_PI * light.mains_hz;
  // Pieces between event times, each linear in t.
  std::vector<double> cuts{t0};
  for (const auto& e : light.events)
    if (e.x() > t0 && e.x() < t1) cuts.push_back(e.x());
  cuts.push_back(t1);
  double sum = 0.0;
  for (size_t i = 0; i + 1 < cuts.size(); ++i) {
    const double a = cuts[i], b = cuts[i + 1];
    if (b <= a) continue;
    // The events' level is linear inside the piece: evaluate it just inside
    // both ends (a switch at a cut belongs to the side it is on).
    const double inside = 1e-9 * (b - a);
    const double la = event_level_at(light.events, a + inside);
    const double lb = event_level_at(light.events, b - inside);
    const double q = (lb - la) / (b - a - 2 * inside);
    const double p = la - q * (a + inside);
    sum += integral_linear_times_flicker(p, q, light.flicker, w, a, b);
  }
  return light.level * sum / (t1 - t0);
}

std::vector<float> row_light_levels(const LightSpec& light, double t, double exposure,
                                    const std::vector<double>& row_offsets) {
  std::vector<float> levels(row_offsets.size());
  for (size_t y = 0; y < row_offsets.size(); ++y) {
    const double mid = t + row_offsets[y];
    levels[y] =
        static_cast<float>(mean_light_level(light, mid - 0.5 * exposure, mid + 0.5 * exposure));
  }
  return levels;
}

}  // namespace depot::sim
