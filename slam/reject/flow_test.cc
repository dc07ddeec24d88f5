#include "slam/reject/flow_test.h"

#include <algorithm>
#include <cmath>

namespace depot::slam {

FlowTestResult mean_static_flow(const std::vector<cv::Point2f>& flow,
                                const std::vector<uint8_t>& ok, const FlowTestParams& params) {
  FlowTestResult r;
  cv::Point2f sum(0, 0);
  for (size_t i = 0; i < flow.size(); ++i) {
    if (!ok[i]) continue;
    sum += flow[i];
    ++r.reference_count;
  }
  if (r.reference_count > 0) r.mean = sum * (1.0f / r.reference_count);
  r.z = std::max(params.z_floor, params.z_factor * std::sqrt(r.mean.dot(r.mean)));
  return r;
}

}  // namespace depot::slam
