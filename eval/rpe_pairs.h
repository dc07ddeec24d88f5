#pragma once
// Which pose pairs (i, j) the relative pose error compares. Every pose i
// starts one pair (evo's `--all_pairs`, TUM evaluate_rpe.py `--fixed_delta`):
//  - frames:  j = i + delta;
//  - seconds: j = the pose whose stamp is closest to t_i + delta, accepted
//    only when that stamp is within `max_time_error` of the target (so the
//    end of the trajectory and tracking gaps give no pairs).
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

namespace depot::eval {

enum class DeltaUnit { kFrames, kSeconds };

std::string to_string(DeltaUnit unit);

struct PairSelection {
  double delta = 1.0;
  DeltaUnit unit = DeltaUnit::kSeconds;
  // Seconds only: largest accepted |t_j - (t_i + delta)|, in s. NaN means
  // half the median stamp spacing, i.e. j must be the frame nearest the target.
  double max_time_error = std::numeric_limits<double>::quiet_NaN();
};

struct PosePair {
  size_t i = 0;
  size_t j = 0;
};

// `stamps` ascending. Throws depot::Error on a non-positive delta, a
// fractional frame delta or a negative time error; may return no pairs.
std::vector<PosePair> select_pose_pairs(const std::vector<double>& stamps,
                                        const PairSelection& selection);

}  // namespace depot::eval
