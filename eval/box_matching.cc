#include "eval/box_matching.h"

#include <algorithm>
#include <numeric>

namespace depot::eval {

double box_iou(const cv::Rect2f& a, const cv::Rect2f& b) {
  const double inter = (a & b).area();
  const double uni = static_cast<double>(a.area()) + b.area() - inter;
  return uni > 0 ? inter / uni : 0.0;
}

Matching no_matches(size_t truth, size_t detections) {
  return {std::vector<int>(detections, -1), std::vector<int>(truth, -1)};
}

void greedy_match(const std::vector<TruthObject>& truth,
                  const std::vector<ScoredDetection>& detections, double min_iou,
                  const std::function<bool(size_t, size_t)>& allowed, Matching& m) {
  std::vector<size_t> order(detections.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return detections[a].confidence > detections[b].confidence;
  });
  for (size_t d : order) {
    if (m.truth_of_detection[d] >= 0) continue;
    int best = -1;
    double best_iou = min_iou;
    for (size_t t = 0; t < truth.size(); ++t) {
      if (m.detection_of_truth[t] >= 0 || !allowed(d, t)) continue;
      const double iou = box_iou(detections[d].box, truth[t].box);
      if (iou >= best_iou && (best < 0 || iou > best_iou)) {
        best = static_cast<int>(t);
        best_iou = iou;
      }
    }
    if (best < 0) continue;
    m.truth_of_detection[d] = best;
    m.detection_of_truth[best] = static_cast<int>(d);
  }
}

}  // namespace depot::eval
