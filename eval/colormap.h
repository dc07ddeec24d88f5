#pragma once
// The perceptually uniform "viridis" colour map (dark blue = low, yellow =
// high), sampled at 11 points and interpolated linearly in RGB.
#include <string>
#include <vector>

namespace depot::eval {

// "#rrggbb" for s in [0, 1] (clamped).
std::string viridis(double s);

// The sample colours from s = 0 to s = 1, for gradients.
std::vector<std::string> viridis_samples();

}  // namespace depot::eval
