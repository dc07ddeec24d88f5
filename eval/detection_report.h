#pragma once
// What `depot eval detector` prints and writes from DetectionScores: a text
// table, JSON with every number, and a report folder (Markdown and a
// self-contained HTML page with recall-vs-box-height plots and confusion
// matrices) that puts several scores side by side, e.g. simulated frames
// and real photos: the sim-to-real gap.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "eval/detection_score.h"

namespace depot::eval {

struct DetectionSide {
  std::string name;      // e.g. "sim: depot_walking_xyz" or "real: photos"
  std::string detector;  // the detector's name
  const DetectionScore* score = nullptr;
  // The detector's labels (empty when unknown): a truth class no label can
  // match is marked in the tables.
  std::vector<std::string> labels;
  double median_ms = 0.0;  // detector time per frame (median)
};

// Every figure of one side.
nlohmann::json detection_side_json(const DetectionSide& side);

// The tables printed on the terminal: per class, by box height, by visible
// fraction, the confusion of clearly visible boxes and false positives.
std::string detection_text(const DetectionSide& side);

// The sides' recall of clearly visible boxes and precision, class by class,
// side by side.
std::string detection_gap_text(const std::vector<DetectionSide>& sides);

// Writes report.md, report.html and recall_vs_height_<i>.svg (one per side)
// into the existing folder `dir`.
void write_detection_report(const std::string& dir, const std::string& title,
                            const std::vector<DetectionSide>& sides);

}  // namespace depot::eval
