#pragma once
// Relative improvement over a baseline, paper Eq. 9:
//   rho = (mu - gamma) / mu * 100 %,
// mu the baseline's error (e.g. ORB-SLAM2's ATE RMSE), gamma ours.
#include <cmath>

#include "common/error.h"

namespace depot::eval {

inline double improvement_percent(double baseline, double ours) {
  if (!std::isfinite(baseline) || baseline <= 0.0) {
    fail("improvement", "baseline error must be a positive number");
  }
  if (!std::isfinite(ours) || ours < 0.0)
    fail("improvement", "error must be a non-negative number");
  return (baseline - ours) / baseline * 100.0;
}

}  // namespace depot::eval
