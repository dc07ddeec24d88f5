#pragma once
// Runs a person segmenter over the frames of a simulated dataset, against
// the label masks of its person instances (labels/ + objects.json), or over
// hand-labelled real images, against their person boxes: what `depot eval
// segmenter` and the tests share.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "eval/image_labels.h"
#include "eval/mask_score.h"
#include "slam/detect/person_segmenter.h"

namespace depot::perception {

struct SegmenterFrame {
  std::string name;            // rgb timestamp or image file
  eval::MaskCounts counts;     // against the label mask (datasets)
  eval::BoxCoverage coverage;  // against the person boxes (labelled images)
  double ms = 0.0;             // segmentation time
};

struct SegmenterEval {
  std::string segmenter;  // its name
  bool boxes = false;     // scored against boxes (labelled images), not masks
  std::vector<SegmenterFrame> frames;

  eval::MaskCounts total() const;  // pixels pooled over the frames
  // Mean of the per-frame IoU over frames whose truth has person pixels.
  double mean_iou() const;
  double median_ms() const;
  nlohmann::json json() const;
  std::string text() const;  // what the terminal shows
};

// Scores frames 0, every, 2 every, ... of `dataset`: the mask (probability
// >= threshold) against the pixels of the instances of class "person".
SegmenterEval evaluate_segmenter(slam::PersonSegmenter& segmenter, const std::string& dataset,
                                 size_t every, bool quiet);

// Scores the labelled images that have person boxes: the share of the mask
// inside the boxes and the share of the boxes it covers.
SegmenterEval evaluate_segmenter_on_images(slam::PersonSegmenter& segmenter,
                                           const eval::ImageLabels& labels, bool quiet);

}  // namespace depot::perception
