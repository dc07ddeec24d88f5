#include "common/tum_association.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>

#include "common/error.h"

namespace depot {
namespace {

struct Candidate {
  double abs_dt;
  double reference_stamp;
  double estimate_stamp;
  size_t reference_index;
  size_t estimate_index;
};

void check_options(const AssociationOptions& options) {
  if (!std::isfinite(options.max_difference) || options.max_difference <= 0.0) {
    fail("association", "max time difference must be a positive number of seconds, got " +
                            std::to_string(options.max_difference));
  }
  if (!std::isfinite(options.offset)) fail("association", "time offset must be finite");
}

// All (reference, estimate) pairs closer than max_difference. Because both
// lists are sorted, only a sliding window of estimates needs checking.
std::vector<Candidate> close_pairs(const std::vector<double>& reference,
                                   const std::vector<double>& estimate,
                                   const AssociationOptions& options) {
  std::vector<Candidate> out;
  size_t first = 0;
  for (size_t r = 0; r < reference.size(); ++r) {
    const double t_ref = reference[r];
    while (first < estimate.size() &&
           estimate[first] + options.offset <= t_ref - options.max_difference) {
      ++first;
    }
    for (size_t e = first; e < estimate.size(); ++e) {
      const double dt = t_ref - (estimate[e] + options.offset);
      if (dt <= -options.max_difference) break;
      if (std::abs(dt) < options.max_difference) {
        out.push_back({std::abs(dt), t_ref, estimate[e], r, e});
      }
    }
  }
  return out;
}

}  // namespace

std::vector<TimestampMatch> associate(const std::vector<double>& reference_stamps,
                                      const std::vector<double>& estimate_stamps,
                                      const AssociationOptions& options) {
  check_options(options);
  std::vector<Candidate> candidates = close_pairs(reference_stamps, estimate_stamps, options);
  // Same order as sorting (|dt|, t_ref, t_est) tuples, so ties break alike.
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    return std::tie(a.abs_dt, a.reference_stamp, a.estimate_stamp) <
           std::tie(b.abs_dt, b.reference_stamp, b.estimate_stamp);
  });

  std::vector<bool> reference_used(reference_stamps.size(), false);
  std::vector<bool> estimate_used(estimate_stamps.size(), false);
  std::vector<TimestampMatch> matches;
  for (const Candidate& c : candidates) {
    if (reference_used[c.reference_index] || estimate_used[c.estimate_index]) continue;
    reference_used[c.reference_index] = true;
    estimate_used[c.estimate_index] = true;
    matches.push_back({c.reference_index, c.estimate_index});
  }
  std::sort(matches.begin(), matches.end(), [](const TimestampMatch& a, const TimestampMatch& b) {
    return a.reference_index < b.reference_index;
  });
  return matches;
}

}  // namespace depot
