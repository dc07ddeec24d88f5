#pragma once
// Camera cover: intervals of a sequence during which something covers the
// RGB-D camera (a hand, a cloth, a robot driving through a dark doorway), so
// that SLAM loses the camera while it keeps moving and must find itself again
// ("kidnapped robot"). What a covered frame holds is decided in
// sim/world/simulated_sequence.cc; here are only the intervals and their rules.
#include <string>
#include <vector>

namespace depot::sim {

// Seconds since the first frame; a frame at time t is covered when
// start <= t < end (half-open, so back-to-back intervals never share a frame).
struct CoverInterval {
  double start = 0.0;
  double end = 0.0;
};

// The problem with `intervals` for a sequence of `duration` seconds (its
// frames span [0, duration)), or "" when they are valid: finite, start >= 0,
// end > start, start before the end of the sequence, end at most `duration`,
// in time order and not overlapping. `duration` <= 0 leaves the upper bound
// unchecked (timestamps read from a file are not known to the loader).
std::string camera_cover_problem(const std::vector<CoverInterval>& intervals, double duration);

// Whether time t (seconds since the first frame) lies in one of the intervals.
bool is_covered(const std::vector<CoverInterval>& intervals, double t);

}  // namespace depot::sim
