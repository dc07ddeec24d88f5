#pragma once
// exposures.txt: how each colour frame was exposed, for systems that model
// photometry (written where the simulated camera forms its colour image:
// light changes, auto-exposure or the colour pipeline). One line per frame:
//
//   timestamp exposure gain light
//
// exposure in seconds, the analogue gain, and the scene's light level at the
// middle row's mid-exposure (1 = as the scene is lit in its layout).
#include <string>
#include <vector>

namespace depot::dataset {

struct ExposureRecord {
  double timestamp = 0;  // the frame's rgb timestamp
  double exposure = 0;   // s
  double gain = 1;
  double light = 1;
};

// Writes `dataset_dir`/exposures.txt atomically, records in frame order.
void write_exposures(const std::string& dataset_dir, const std::string& scenario_name,
                     const std::vector<ExposureRecord>& records);

// Reads `dataset_dir`/exposures.txt after checking the dataset's format
// version. Throws depot::Error "<path>:<line>: ..." for a malformed line
// (field count, numbers, a negative exposure, gain below 1, negative light).
std::vector<ExposureRecord> read_exposures(const std::string& dataset_dir);

}  // namespace depot::dataset
