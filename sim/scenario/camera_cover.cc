#include "sim/scenario/camera_cover.h"

#include <fmt/format.h>

#include <cmath>

namespace depot::sim {

namespace {

std::string seconds(double v) {
  return fmt::format("{:g}", v);
}

std::string describe(size_t index, const CoverInterval& c) {
  return "interval " + std::to_string(index + 1) + " [" + seconds(c.start) + ", " + seconds(c.end) +
         "]";
}

}  // namespace

std::string camera_cover_problem(const std::vector<CoverInterval>& intervals, double duration) {
  for (size_t i = 0; i < intervals.size(); ++i) {
    const CoverInterval& c = intervals[i];
    const std::string what = describe(i, c);
    if (!std::isfinite(c.start) || !std::isfinite(c.end)) return what + " is not finite";
    if (c.start < 0.0) return what + " starts before the first frame (seconds from 0)";
    if (c.end <= c.start) return what + " must end after it starts";
    if (duration > 0.0 && c.start >= duration)
      return what + " starts after the last frame (the sequence lasts " + seconds(duration) + " s)";
    if (duration > 0.0 && c.end > duration)
      return what + " ends after the last frame (the sequence lasts " + seconds(duration) + " s)";
    if (i > 0 && c.start < intervals[i - 1].end)
      return what + " overlaps or comes before " + describe(i - 1, intervals[i - 1]) +
             " (list them in time order, apart)";
  }
  return "";
}

bool is_covered(const std::vector<CoverInterval>& intervals, double t) {
  for (const CoverInterval& c : intervals)
    if (t >= c.start && t < c.end) return true;
  return false;
}

}  // namespace depot::sim
