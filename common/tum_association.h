#pragma once
// Pairs two lists of timestamps the way TUM's associate.py does: every pair
// with |t_ref - (t_est + offset)| < max_difference is a candidate, candidates
// are taken greedily from the smallest |dt| up, and each stamp is used at most
// once. Stamps without a partner are dropped.
#include <cstddef>
#include <vector>

namespace depot {

struct AssociationOptions {
  double max_difference = 0.02;  // s, strict upper bound on |dt|
  double offset = 0.0;           // s, added to the estimate's stamps
};

struct TimestampMatch {
  size_t reference_index = 0;
  size_t estimate_index = 0;
};

// Both lists must be sorted ascending. The result is sorted by reference
// stamp. Throws depot::Error on invalid options.
std::vector<TimestampMatch> associate(const std::vector<double>& reference_stamps,
                                      const std::vector<double>& estimate_stamps,
                                      const AssociationOptions& options = {});

}  // namespace depot
