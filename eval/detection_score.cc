#include "eval/detection_score.h"
#include "common/number_text.h"

#include <algorithm>
#include <cmath>

namespace depot::eval {
namespace {

size_t bucket(const std::vector<double>& edges, double v) {
  return static_cast<size_t>(std::upper_bound(edges.begin(), edges.end(), v) - edges.begin());
}

std::vector<std::string> bucket_names(const std::vector<double>& edges) {
  std::vector<std::string> names;
  if (edges.empty()) return {"all"};
  names.push_back("<" + shortest_number(edges.front()));
  for (size_t i = 1; i < edges.size(); ++i)
    names.push_back(shortest_number(edges[i - 1]) + "-" + shortest_number(edges[i]));
  names.push_back(">=" + shortest_number(edges.back()));
  return names;
}

}  // namespace

bool DetectionRules::clearly_visible(const TruthObject& box) const {
  return box.box.height >= clear_min_height && box.visible_pixels >= clear_min_visible;
}

size_t DetectionRules::height_bucket(const TruthObject& box) const {
  return bucket(height_edges, box.box.height);
}

size_t DetectionRules::fill_bucket(const TruthObject& box) const {
  const double area = box.box.area();
  return bucket(fill_edges, area > 0 ? box.visible_pixels / area : 0.0);
}

std::vector<std::string> DetectionRules::height_bucket_names() const {
  return bucket_names(height_edges);
}

std::vector<std::string> DetectionRules::fill_bucket_names() const {
  return bucket_names(fill_edges);
}

FrameMatch match_frame(const std::vector<TruthObject>& truth,
                       const std::vector<ScoredDetection>& detections, const ClassMapping& mapping,
                       double min_iou) {
  FrameMatch out{{}, no_matches(truth.size(), detections.size())};
  greedy_match(
      truth, detections, min_iou,
      [&](size_t d, size_t t) { return mapping.matches(detections[d].label, truth[t].class_name); },
      out.any);
  out.by_class = out.any.detection_of_truth;
  greedy_match(
      truth, detections, min_iou, [](size_t, size_t) { return true; }, out.any);
  return out;
}

double Tally::rate() const {
  return total > 0 ? static_cast<double>(found) / total : NAN;
}

DetectionScore::DetectionScore(std::vector<std::string> classes, ClassMapping mapping,
                               DetectionRules rules)
    : classes_(std::move(classes)), mapping_(std::move(mapping)), rules_(std::move(rules)) {
  for (const std::string& c : classes_) mutable_tally(c);
}

std::vector<std::string> DetectionScore::classes() const {
  std::vector<std::string> all = classes_;
  all.insert(all.end(), extra_classes_.begin(), extra_classes_.end());
  return all;
}

const ClassTally& DetectionScore::tally(const std::string& class_name) const {
  static const ClassTally kEmpty;
  const auto it = tallies_.find(class_name);
  return it == tallies_.end() ? kEmpty : it->second;
}

ClassTally& DetectionScore::mutable_tally(const std::string& class_name) {
  auto it = tallies_.find(class_name);
  if (it != tallies_.end()) return it->second;
  if (std::find(classes_.begin(), classes_.end(), class_name) == classes_.end())
    extra_classes_.push_back(class_name);
  ClassTally t;
  t.by_height.resize(rules_.height_edges.size() + 1);
  t.by_fill.resize(rules_.fill_edges.size() + 1);
  return tallies_.emplace(class_name, std::move(t)).first->second;
}

void DetectionScore::add_frame(const std::vector<TruthObject>& truth,
                               const std::vector<ScoredDetection>& detections) {
  ++frames_;
  const FrameMatch match = match_frame(truth, detections, mapping_, rules_.min_iou);
  const std::vector<int>& by_class = match.by_class;
  const Matching& m = match.any;

  for (size_t t = 0; t < truth.size(); ++t) {
    const TruthObject& box = truth[t];
    const bool found = by_class[t] >= 0;
    const bool clear = rules_.clearly_visible(box);
    ClassTally& tally = mutable_tally(box.class_name);
    tally.all.add(found);
    if (clear) tally.clear.add(found);
    if (!box.model.empty()) {
      ModelTally& mt = by_model_[box.class_name][box.model];
      mt.all.add(found);
      if (clear) mt.clear.add(found);
    }
    tally.by_height[rules_.height_bucket(box)].add(found);
    tally.by_fill[rules_.fill_bucket(box)].add(found);
    if (found) tally.iou_sum += box_iou(detections[by_class[t]].box, box.box);
    const int d = m.detection_of_truth[t];
    const std::string called = d >= 0 ? mapping_.class_of(detections[d].label) : kMissed;
    ++confusion_[box.class_name][called];
    if (clear) ++confusion_clear_[box.class_name][called];
  }
  for (size_t d = 0; d < detections.size(); ++d) {
    if (!mapping_.relevant(detections[d].label, classes_)) {
      ++other_detections_;
      continue;
    }
    const int t = m.truth_of_detection[d];
    const bool correct = t >= 0 && by_class[t] == static_cast<int>(d);
    mutable_tally(mapping_.class_of(detections[d].label)).precision.add(correct);
    false_positives_ += !correct;
  }
}

double DetectionScore::false_positives_per_frame() const {
  return frames_ > 0 ? static_cast<double>(false_positives_) / frames_ : NAN;
}

}  // namespace depot::eval
