#pragma once
// Configuration of the simulated detector (sim_detector.h): how it degrades
// the simulator's ground-truth boxes the way a real YOLO does. The defaults
// below are a generic YOLOv5s-like guess; `depot slam run --detector sim`
// and the tests use scenes/detectors/sim.yaml instead, the error model fitted
// to the real Yolo-Fastest 1.1 on simulated frames (`depot eval calibrate`).
//
// YAML form (every key optional, names as the fields below):
//
//   seed: 1
//   miss_rate: 0.05
//   class_miss_rate: {desk: 0.95}                  # replaces miss_rate per class
//   class_confusion_rate: {dog: 0.7}               # replaces class_confusion per class
//   small_miss_boost: 0.6
//   confusions: {dog: [cat, pig], chair: [cart]}   # replaces the default table
//   latency_frames: 0
//   calibration: {...}   # how the values were measured; read by people, not checked
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace YAML {
class Node;
}

namespace depot::slam {

struct SimDetectorConfig {
  // Base seed; frame i draws from depot::derive_seed(seed, i, ...), so every
  // frame is reproducible on its own, in any order.
  uint64_t seed = 1;
  // Return the ground-truth boxes unchanged (confidence 1). Latency still
  // applies; every other degradation is off.
  bool perfect = false;

  // --- Missed detections -------------------------------------------------
  // A box is missed with probability
  //   1 - (1 - miss_rate) (1 - small_miss_boost s) (1 - occlusion_miss o)
  // where s = smallness, o = occlusion, both in [0, 1] (sim_detector.h).
  // Probability of missing a large, unoccluded box.
  double miss_rate = 0.05;
  // The same per class (class -> rate), replacing miss_rate for that class:
  // real detectors find some classes far more reliably than others. Classes
  // that are not in the dataset's classes.txt are ignored. A YAML map that
  // sets miss_rate without class_miss_rate (e.g. `--detector-set
  // miss_rate=0.2`, a sweep's miss_rate levels) drops the per-class rates it
  // starts from: one rate for every class.
  std::map<std::string, double> class_miss_rate;
  // Extra miss probability of a vanishingly small box (s = 1).
  double small_miss_boost = 0.6;
  // Box area, as a fraction of the image area, from which a box counts as
  // large (s = 0): s = 1 - sqrt(area / small_area), i.e. linear in the box's
  // side. 0.01 is 64 x 48 px at 640 x 480; a COCO "small" 32 x 32 px box
  // gets s = 0.42.
  double small_area = 0.01;
  // Extra miss probability of a fully occluded box (o = 1).
  double occlusion_miss = 0.5;
  // Occlusion compares a box's fill (visible pixels / box area) with the fill
  // of an unoccluded object of its class, taken as the 90th percentile of
  // that class's fills over the dataset's boxes.txt. Classes with fewer than
  // 10 boxes there use this value instead.
  double default_fill = 0.5;

  // --- Localisation ------------------------------------------------------
  // Standard deviation of the box centre's shift, as a fraction of the box's
  // width (x) and height (y).
  double jitter = 0.03;
  // Standard deviation of the log of the width and height scale factors
  // (independent per axis): 0.05 = about +-5 % size error.
  double scale_error = 0.05;
  // Hard boxes are localised worse: both sigmas above are multiplied by
  // (1 + hard_jitter_gain d), d = difficulty in [0, 1].
  double hard_jitter_gain = 1.0;

  // --- Confidence --------------------------------------------------------
  // Output threshold of the detector: no detection scores below it.
  double min_confidence = 0.3;
  // Mean confidence of an easy box (d = 0). The mean falls linearly with the
  // difficulty d, by confidence_drop x (max_confidence - min_confidence) at
  // d = 1.
  double max_confidence = 0.95;
  // How far the mean confidence falls at d = 1, as a fraction of the way
  // from max_confidence down to min_confidence: 1 = all the way (a hard box
  // scores about min_confidence), 0 = confidence does not depend on d.
  double confidence_drop = 1.0;
  // Standard deviation of the confidence around that mean (then clamped to
  // [min_confidence, 1]).
  double confidence_noise = 0.05;

  // --- False positives ---------------------------------------------------
  // Mean number of false boxes per frame (Poisson). Each has a random class
  // from classes.txt, the size of a random ground-truth box of that class
  // (scaled by up to about +-35 %; a generic size when the class has none),
  // a random place inside the image, and a confidence uniform in
  // [min_confidence, false_positive_max_confidence]. They come from their
  // own random stream: changing this rate leaves the detections of real
  // objects unchanged.
  double false_positive_rate = 0.05;
  double false_positive_max_confidence = 0.5;

  // --- Class confusion ---------------------------------------------------
  // Probability that a detected box of a class that has confusion partners
  // is labelled as one of them (chosen uniformly). Confused boxes score as
  // hard boxes (d >= 0.5).
  double class_confusion = 0.02;
  // The same per class (class -> probability), replacing class_confusion for
  // that class. A YAML map that sets class_confusion without
  // class_confusion_rate drops the per-class rates it starts from.
  std::map<std::string, double> class_confusion_rate;
  // class -> classes it is mistaken for. Pairs naming a class that is not in
  // the dataset's classes.txt are ignored.
  std::map<std::string, std::vector<std::string>> confusions = {
      {"dog", {"cat", "pig"}}, {"cat", {"dog"}},    {"pig", {"dog"}},   {"bird", {"cat"}},
      {"chair", {"cart"}},     {"cart", {"chair"}}, {"desk", {"chair"}}};

  // --- Timing ------------------------------------------------------------
  // The detector lags k frames: frame i gets the detections of frame i - k
  // (none for i < k), as when the detection thread is k frames behind.
  int latency_frames = 0;
};

// Reads a config from a YAML map: keys as the fields above, absent keys keep
// `defaults`. Throws depot::Error "<where>[:line]: <problem>" for an unknown
// key, a value of the wrong type, a probability outside [0, 1], a latency
// outside 0..30 or inconsistent confidences (min < max, min <= false positive
// max). A null node gives `defaults`. The key `calibration` (a map: what the
// values were fitted on, see `depot eval calibrate`) is accepted and ignored.
SimDetectorConfig load_sim_detector_config(const YAML::Node& node, const std::string& where,
                                           const SimDetectorConfig& defaults = {});

// The same from a YAML file whose top level is that map.
SimDetectorConfig load_sim_detector_config_file(const std::string& path,
                                                const SimDetectorConfig& defaults = {});

// Checks the ranges above; throws depot::Error "<where>: <problem>".
void validate(const SimDetectorConfig& config, const std::string& where);

}  // namespace depot::slam
