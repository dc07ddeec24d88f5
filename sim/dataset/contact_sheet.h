#pragma once
// `depot sim preview`: a contact sheet of a dataset (RGB, depth colour-mapped,
// instance labels with boxes) for people to look at.
#include <string>

namespace depot::sim {

struct ContactSheetOptions {
  int rows = 4;  // frames shown, evenly spread over the sequence
  int thumb_width = 320;
};

// Reads DATASET (a TUM folder written by the simulator, or any TUM RGB-D
// folder; labels are shown when present) and writes a PNG/JPG sheet.
void write_contact_sheet(const std::string& dataset, const std::string& output,
                         const ContactSheetOptions& options);

}  // namespace depot::sim
