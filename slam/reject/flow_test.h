#pragma once
// PAPER.md Eq. 6-7: the mean static flow [U V] over the reference points and
// the threshold test |(u, v) - (U, V)| > z with z = factor x |[U V]|, floored
// so that a still camera does not give z = 0.
#include <vector>

#include <opencv2/core.hpp>

namespace depot::slam {

struct FlowTestParams {
  float z_factor = 2.0f;  // the paper's "twice the static mean flow"
  float z_floor = 1.5f;   // px
};

struct FlowTestResult {
  cv::Point2f mean{0, 0};  // [U V]
  float z = 0;             // threshold used
  int reference_count = 0;
};

// Mean over the reference flows that tracked (ok).
FlowTestResult mean_static_flow(const std::vector<cv::Point2f>& reference_flow,
                                const std::vector<uint8_t>& ok, const FlowTestParams& params);

// True when the flow deviates from the mean by more than z (Eq. 7).
inline bool flow_is_dynamic(const cv::Point2f& flow, const FlowTestResult& t) {
  const cv::Point2f d = flow - t.mean;
  return d.dot(d) > t.z * t.z;
}

}  // namespace depot::slam
