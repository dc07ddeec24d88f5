#pragma once
// The standard rBRIEF sampling pattern used for ORB descriptors.
#include <cstdint>

namespace depot::slam {

// Number of intensity tests (= descriptor bits).
inline constexpr int kOrbPatternPairs = 256;

// kOrbPattern[4 * k + 0..3] = (x1, y1, x2, y2) of test k: bit k of a descriptor is
// I(x1, y1) < I(x2, y2) on the smoothed level image, after rotating both points by
// the keypoint angle. All offsets lie in [-13, 12].
extern const std::int8_t kOrbPattern[kOrbPatternPairs * 4];

}  // namespace depot::slam
