#pragma once
// Nearest-rank percentile of timing samples (p in [0, 1]; 0 for none), as
// the programs and benchmarks report them.
#include <algorithm>
#include <vector>

namespace depot {

inline double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(p * (v.size() - 1) + 0.5))];
}

}  // namespace depot
