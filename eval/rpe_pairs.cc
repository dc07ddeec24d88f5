#include "eval/rpe_pairs.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "common/number_text.h"

namespace depot::eval {
namespace {

void check_selection(const PairSelection& s) {
  if (!std::isfinite(s.delta) || s.delta <= 0.0) {
    fail("relative pose error", "delta must be positive, got " + shortest_number(s.delta));
  }
  if (s.unit == DeltaUnit::kFrames && s.delta != std::floor(s.delta)) {
    fail("relative pose error",
         "a delta in frames must be a whole number, got " + shortest_number(s.delta));
  }
  if (s.max_time_error < 0.0 || std::isinf(s.max_time_error)) {
    fail("relative pose error", "the accepted time error must be a non-negative number");
  }
}

// Index of the stamp closest to t (the earlier one on a tie).
size_t closest_index(const std::vector<double>& stamps, double t) {
  const auto after = std::lower_bound(stamps.begin(), stamps.end(), t);
  if (after == stamps.begin()) return 0;
  if (after == stamps.end()) return stamps.size() - 1;
  const auto before = after - 1;
  return static_cast<size_t>((t - *before <= *after - t ? before : after) - stamps.begin());
}

double half_median_spacing(const std::vector<double>& stamps) {
  if (stamps.size() < 2) return 0.0;
  std::vector<double> spacing;
  for (size_t k = 1; k < stamps.size(); ++k) spacing.push_back(stamps[k] - stamps[k - 1]);
  const size_t mid = spacing.size() / 2;
  std::nth_element(spacing.begin(), spacing.begin() + static_cast<std::ptrdiff_t>(mid),
                   spacing.end());
  return 0.5 * spacing[mid];
}

}  // namespace

std::string to_string(DeltaUnit unit) {
  return unit == DeltaUnit::kFrames ? "frames" : "s";
}

std::vector<PosePair> select_pose_pairs(const std::vector<double>& stamps,
                                        const PairSelection& selection) {
  check_selection(selection);
  std::vector<PosePair> pairs;
  if (selection.unit == DeltaUnit::kFrames) {
    if (selection.delta >= static_cast<double>(stamps.size())) return pairs;
    const auto step = static_cast<size_t>(selection.delta);
    for (size_t i = 0; i + step < stamps.size(); ++i) pairs.push_back({i, i + step});
    return pairs;
  }
  const double max_miss =
      std::isnan(selection.max_time_error) ? half_median_spacing(stamps) : selection.max_time_error;
  const double bound = max_miss * (1.0 + 1e-9) + 1e-12;  // stamps carry rounding noise
  for (size_t i = 0; i < stamps.size(); ++i) {
    const double target = stamps[i] + selection.delta;
    const size_t j = closest_index(stamps, target);
    if (j > i && std::abs(stamps[j] - target) <= bound) pairs.push_back({i, j});
  }
  return pairs;
}

}  // namespace depot::eval
