#include "eval/statistics.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"

namespace depot::eval {

ErrorStatistics compute_statistics(const std::vector<double>& errors) {
  if (errors.empty()) fail("statistics", "no errors to summarise");
  for (double e : errors) {
    if (!std::isfinite(e)) fail("statistics", "an error value is not finite");
  }
  ErrorStatistics s;
  s.count = errors.size();
  const double n = static_cast<double>(errors.size());

  double sum = 0.0;
  for (double e : errors) {
    sum += e;
    s.sse += e * e;
  }
  s.mean = sum / n;
  s.rmse = std::sqrt(s.sse / n);

  double squared_deviation = 0.0;
  for (double e : errors) squared_deviation += (e - s.mean) * (e - s.mean);
  s.std = std::sqrt(squared_deviation / n);

  std::vector<double> sorted = errors;
  std::sort(sorted.begin(), sorted.end());
  s.min = sorted.front();
  s.max = sorted.back();
  const size_t mid = sorted.size() / 2;
  s.median = sorted.size() % 2 == 1 ? sorted[mid] : 0.5 * (sorted[mid - 1] + sorted[mid]);
  return s;
}

}  // namespace depot::eval
