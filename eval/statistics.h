#pragma once
// Summary figures of a list of errors, defined as evo and TUM's tools define
// them: RMSE = sqrt(mean of squares), median of an even count = mean of the
// two middle values, std = population standard deviation (numpy.std).
#include <cstddef>
#include <vector>

namespace depot::eval {

struct ErrorStatistics {
  size_t count = 0;
  double rmse = 0.0;
  double mean = 0.0;
  double median = 0.0;
  double std = 0.0;
  double min = 0.0;
  double max = 0.0;
  double sse = 0.0;  // sum of squares
};

// Throws depot::Error on an empty list or a non-finite value.
ErrorStatistics compute_statistics(const std::vector<double>& errors);

}  // namespace depot::eval
