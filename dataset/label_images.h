#pragma once
// The instance label images: labels/<timestamp>.png, 16-bit, each pixel the
// id of the instance it shows (objects.json), 0 for none; and their list
// labels.txt, a TUM file list ("timestamp labels/<timestamp>.png").
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "common/tum_io.h"

namespace depot::dataset {

// The label image of the frame with this rgb timestamp, relative to the
// dataset folder.
std::string label_image_name(double timestamp);

// Writes labels.txt atomically: one line per frame (rgb timestamps, in
// order).
void write_label_list(const std::string& dataset_dir, const std::string& scenario_name,
                      const std::vector<double>& timestamps);
// Writes one label image (CV_16UC1) at `compression_level` (zlib 0..9);
// returns the bytes written.
size_t write_label_image(const std::string& dataset_dir, double timestamp, const cv::Mat& labels,
                         int compression_level);

// Whether the folder has a label list (a rendered simulated dataset).
bool has_label_list(const std::string& dataset_dir);
// Reads labels.txt after checking the dataset's format version. Throws
// depot::Error naming the file (and line) when it is missing or malformed.
std::vector<StampedFile> read_label_list(const std::string& dataset_dir);
// The label image at `relative_path` (a labels.txt entry). Throws
// depot::Error naming it when it is unreadable or not 16-bit single-channel.
cv::Mat read_label_image(const std::string& dataset_dir, const std::string& relative_path);

}  // namespace depot::dataset
