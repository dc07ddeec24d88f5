#pragma once
// Fitting the simulated detector's error model (sim_detector.h) to what a
// detector did on simulated frames: `depot eval calibrate` collects, for
// every ground-truth box, whether the detector found it (under its own class,
// under another class of the simulator, or not at all), how far off its box
// was and how confident it was; this fits the model's parameters to that.
//
// How each parameter is fitted (d = difficulty, s = smallness, o = occlusion,
// as the simulated detector computes them):
// - The miss model, by maximum likelihood over all boxes: a box is matched
//   (at IoU >= 0.5, any class) with probability
//     (1 - m_c)(1 - small_miss_boost s)(1 - occlusion_miss o) r(d)
//   where m_c is the class's miss rate (class_miss_rate, one per class with
//   boxes; profiled out), and r(d) the probability that the simulator's
//   localisation error (below) keeps the box at IoU >= 0.5, so that the
//   simulated detector re-run on the same boxes matches as often as the real
//   one. small_miss_boost, occlusion_miss and small_area by Nelder-Mead on
//   the profile likelihood; miss_rate (classes not measured) is the pooled
//   rate of all measured boxes.
// - jitter, scale_error and hard_jitter_gain, by maximum likelihood over the
//   matched boxes: centre shift / size ~ N(0, jitter g), log size ratio ~
//   N(0, scale_error g), g = 1 + hard_jitter_gain d (the gain profiled on
//   [0, 10]). Only matched boxes (IoU >= 0.5) are seen, so large errors are
//   somewhat under-represented.
// - max_confidence, confidence_drop and confidence_noise, by least squares
//   of the matched boxes' confidences on max - (max - min) drop d;
//   min_confidence is the detector's threshold (given), clamping ignored.
// - confusions: exactly the pairs observed; class_confusion_rate: confused /
//   matched boxes of each class with a partner; class_confusion (classes
//   without a rate of their own): the same pooled over those classes.
// - false_positive_rate: unmatched detections per frame, less the ones the
//   simulator makes itself when its localisation error takes a detection
//   below IoU 0.5 (their expected number under the fit);
//   false_positive_max_confidence: the upper end of a uniform distribution
//   from min_confidence with the rest's mean confidence.
// The miss model, r(d) and the localisation depend on each other through
// small_area and the sigmas: they are fitted in turn, three rounds.
#include <map>
#include <string>
#include <vector>

#include "slam/detect/sim_detector_config.h"

namespace depot::perception {

// One ground-truth box and what the detector under calibration made of it.
struct FitBox {
  std::string truth_class;
  double area = 0;        // box area, pixels
  double image_area = 0;  // pixels
  double occlusion = 0;   // SimDetector::occlusion(), in [0, 1]
  // The class it was matched as: truth_class (found), another class of the
  // simulator (confused), or "" (missed: no detection at IoU >= 0.5, or one
  // with a label the simulator has no class for).
  std::string detected_class;
  // When matched: the detection's centre shift as a fraction of the box's
  // width (dx) and height (dy), log of its width and height ratios, and its
  // confidence.
  double dx = 0, dy = 0, log_w = 0, log_h = 0;
  double confidence = 0;

  bool matched() const { return !detected_class.empty(); }
  bool confused() const { return matched() && detected_class != truth_class; }
};

struct FitData {
  std::vector<FitBox> boxes;
  long frames = 0;
  // Confidences of the detections that matched no box.
  std::vector<double> false_positive_confidences;
  // The detector's output threshold, which becomes min_confidence.
  double min_confidence = 0.3;
};

struct ClassFit {
  long boxes = 0, found = 0, confused = 0;
  double miss_rate = 1.0;  // fitted m_c
};

struct SimDetectorFit {
  // `base` with every fitted key replaced (seed, default_fill and
  // latency_frames are kept; perfect is off).
  slam::SimDetectorConfig config;
  std::map<std::string, ClassFit> classes;  // per truth class with boxes
  long boxes = 0, matched = 0, confused = 0, false_positives = 0, frames = 0;
  double miss_log_likelihood = 0;  // of the miss model at the fit, nats
  // Of the unmatched detections, how many the fitted model expects from
  // boxes detected below IoU 0.5 (the rest are its false positives).
  double off_target = 0;
};

// Fits the model to `data`. Throws depot::Error "<where>: <problem>" when a
// parameter has nothing to be fitted on: no boxes, no frame, no matched box
// (localisation and confidences), no partly occluded box of a class the
// detector matched (occlusion_miss).
SimDetectorFit fit_sim_detector(const FitData& data, const slam::SimDetectorConfig& base,
                                const std::string& where);

// The probability that a box keeps IoU >= `min_iou` with itself after the
// simulated detector's localisation error at these sigmas (centre shift
// sigma `jitter` of the size, log size sigma `scale_error`), unclipped; by a
// fixed Monte Carlo sample, so the same arguments give the same value.
double iou_retention(double jitter, double scale_error, double min_iou = 0.5);

}  // namespace depot::perception
