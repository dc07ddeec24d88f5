#pragma once
// info.json: what made a dataset (generator, scenario, seeds, styles, ...)
// and the format version of its truth files. It also marks the folder as
// the simulator's own (common/staged_directory.h).
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace depot::dataset {

struct DatasetInfo {
  int format_version = 0;  // as read (1 when the file states none); writing states kFormatVersion
  std::string generator;   // e.g. "depot-slam simulator"
  std::string scenario;
  std::optional<std::string> description;  // rendered datasets only
  std::optional<uint64_t> seed;
  std::optional<uint64_t> world_seed;  // draws the world; the seed unless set apart
  std::optional<long> frames;
  std::optional<double> dynamic_load;
  std::string actors_style, props_style;  // "" when not stated
  std::optional<std::string> sensor;      // "kinect" or "ideal"; rendered datasets only
  std::string motion;                     // camera motion type
  // Seconds the camera is covered, as the scenario writes them, and the
  // frames (first and last index) they cover. Both written when the first
  // is not empty.
  std::vector<std::pair<double, double>> camera_cover;
  std::vector<std::pair<long, long>> covered_frames;
};

// The file's text (pretty-printed, keys in name order, format_version =
// kFormatVersion).
std::string format_info(const DatasetInfo& info);
// Writes `dataset_dir`/info.json atomically.
void write_info(const std::string& dataset_dir, const DatasetInfo& info);

// `dataset_dir`/info.json, or nothing when the folder has none. Throws
// depot::Error naming the file when it is malformed, a member has the wrong
// type, or its format_version is newer than this program reads.
std::optional<DatasetInfo> read_info(const std::string& dataset_dir);

}  // namespace depot::dataset
