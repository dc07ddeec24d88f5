#include "eval/colormap.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace depot::eval {
namespace {

struct Rgb {
  double r, g, b;
};

// viridis at s = 0, 0.1, ..., 1.
constexpr std::array<Rgb, 11> kViridis = {{{68, 1, 84},
                                           {72, 36, 117},
                                           {65, 68, 135},
                                           {53, 95, 141},
                                           {42, 120, 142},
                                           {33, 145, 140},
                                           {34, 168, 132},
                                           {68, 191, 112},
                                           {122, 209, 81},
                                           {189, 223, 38},
                                           {253, 231, 37}}};

std::string hex(const Rgb& c) {
  auto byte = [](double v) { return static_cast<int>(std::lround(std::clamp(v, 0.0, 255.0))); };
  return fmt::format("#{:02x}{:02x}{:02x}", byte(c.r), byte(c.g), byte(c.b));
}

}  // namespace

std::string viridis(double s) {
  if (!std::isfinite(s)) s = 0.0;
  s = std::clamp(s, 0.0, 1.0);
  const double scaled = s * (kViridis.size() - 1);
  const auto k = std::min(static_cast<size_t>(scaled), kViridis.size() - 2);
  const double f = scaled - static_cast<double>(k);
  const Rgb& a = kViridis[k];
  const Rgb& b = kViridis[k + 1];
  return hex({a.r + f * (b.r - a.r), a.g + f * (b.g - a.g), a.b + f * (b.b - a.b)});
}

std::vector<std::string> viridis_samples() {
  std::vector<std::string> out;
  for (const Rgb& c : kViridis) out.push_back(hex(c));
  return out;
}

}  // namespace depot::eval
