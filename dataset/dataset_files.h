#pragma once
// The file names of a simulated dataset's truth files and the pieces their
// text forms share. One place, so writers and readers cannot drift apart.
#include <string>

namespace depot::dataset {

inline constexpr const char* kInfoFile = "info.json";
inline constexpr const char* kLabelListFile = "labels.txt";
inline constexpr const char* kLabelFolder = "labels";
inline constexpr const char* kObjectsFile = "objects.json";
inline constexpr const char* kObjectPosesFile = "object_poses.txt";
inline constexpr const char* kBoxesFile = "boxes.txt";
inline constexpr const char* kExposuresFile = "exposures.txt";

// `dataset_dir`/`name`.
std::string dataset_file(const std::string& dataset_dir, const std::string& name);

// A frame's timestamp as every dataset file writes it ("%.6f"): the key that
// joins the files' lines to one frame.
std::string format_timestamp(double t);

// The second comment line of every text file of a dataset.
std::string file_header_line(const std::string& scenario_name);

}  // namespace depot::dataset
