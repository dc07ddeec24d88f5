#pragma once
// Scoring a detector against ground-truth boxes, frame by frame: recall and
// precision per class at IoU >= 0.5 (greedy matching by confidence, classes
// compared after the detector's class mapping), recall by box height and by
// visible fraction, and a class confusion matrix.
//
// Rules (issue 10's measurement):
// - A truth box is "clearly visible" when it is at least 100 px tall and has
//   at least 4000 visible pixels; recall is reported for all boxes and for
//   the clearly visible ones. Precision counts every box (a detection of a
//   barely visible object is not a false positive).
// - Precision is per detected class (the class a label maps to) over the
//   detections that could stand for a scored class (ClassMapping::relevant);
//   detections of other labels ("bottle") are counted apart.
// - Confusion: truth class x detected class. Boxes matched with the class
//   rule are on their detection's class (for pig: the animal it was called);
//   the rest are then matched to the remaining detections of any class at
//   IoU >= 0.5 (same greedy rule), else "missed".
#include <map>
#include <string>
#include <vector>

#include "eval/box_matching.h"
#include "eval/class_mapping.h"

namespace depot::eval {

struct DetectionRules {
  double min_iou = 0.5;
  double clear_min_height = 100.0;    // px
  double clear_min_visible = 4000.0;  // px
  // Bucket edges: box height (px) and visible fraction (visible pixels /
  // box area); n edges make n + 1 buckets.
  std::vector<double> height_edges{50, 100, 200};
  std::vector<double> fill_edges{0.25, 0.5, 0.75};

  bool clearly_visible(const TruthObject& box) const;
  size_t height_bucket(const TruthObject& box) const;
  size_t fill_bucket(const TruthObject& box) const;
  // "<50", "50-100", "100-200", ">=200" and "<0.25", ..., ">=0.75".
  std::vector<std::string> height_bucket_names() const;
  std::vector<std::string> fill_bucket_names() const;
};

// The matching of one frame by the rules above: `by_class[t]` is the
// detection that found truth box t under the class rule (-1: none); `any`
// holds those pairs and then the pairs of any class among what they left.
struct FrameMatch {
  std::vector<int> by_class;
  Matching any;
};
FrameMatch match_frame(const std::vector<TruthObject>& truth,
                       const std::vector<ScoredDetection>& detections, const ClassMapping& mapping,
                       double min_iou);

// found of total; rate() is NaN when total is 0.
struct Tally {
  long found = 0, total = 0;
  double rate() const;
  void add(bool hit) {
    ++total;
    found += hit;
  }
};

struct ClassTally {
  Tally all, clear;                       // recall of this class's truth boxes
  std::vector<Tally> by_height, by_fill;  // recall of all its boxes, per bucket
  Tally precision;       // of the relevant detections counted as this class: matched
  double iou_sum = 0.0;  // over the matched truth boxes (mean IoU = iou_sum / all.found)
};

class DetectionScore {
 public:
  static constexpr const char* kMissed = "missed";

  // `classes`: the truth's classes (classes.txt, or a labels file's list),
  // which order the tables.
  DetectionScore(std::vector<std::string> classes, ClassMapping mapping, DetectionRules rules = {});

  void add_frame(const std::vector<TruthObject>& truth,
                 const std::vector<ScoredDetection>& detections);

  const std::vector<std::string>& truth_classes() const { return classes_; }
  // Every class with a tally: the truth classes, then detected classes.
  std::vector<std::string> classes() const;
  // The tally of a class (an empty one when nothing was seen of it).
  const ClassTally& tally(const std::string& class_name) const;
  // truth class -> detected class or kMissed -> boxes; all boxes, and the
  // clearly visible ones.
  // Recall per catalogue model of the boxes that name one (TruthObject::
  // model): class -> model -> {all, clear} tallies.
  struct ModelTally {
    Tally all, clear;
  };
  const std::map<std::string, std::map<std::string, ModelTally>>& by_model() const {
    return by_model_;
  }

  const std::map<std::string, std::map<std::string, long>>& confusion(bool clear_only) const {
    return clear_only ? confusion_clear_ : confusion_;
  }

  long frames() const { return frames_; }
  // Relevant detections matching no truth box of their class.
  long false_positives() const { return false_positives_; }
  // Detections of labels that stand for no truth class (not scored).
  long other_detections() const { return other_detections_; }
  double false_positives_per_frame() const;

  const DetectionRules& rules() const { return rules_; }
  const ClassMapping& mapping() const { return mapping_; }

 private:
  ClassTally& mutable_tally(const std::string& class_name);

  std::vector<std::string> classes_;
  ClassMapping mapping_;
  DetectionRules rules_;
  std::map<std::string, ClassTally> tallies_;
  std::vector<std::string> extra_classes_;  // detected classes beyond classes_
  std::map<std::string, std::map<std::string, long>> confusion_, confusion_clear_;
  std::map<std::string, std::map<std::string, ModelTally>> by_model_;
  long frames_ = 0, false_positives_ = 0, other_detections_ = 0;
};

}  // namespace depot::eval
