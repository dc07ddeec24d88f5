#include "dataset/label_images.h"

#include <filesystem>

#include "common/error.h"
#include "common/png_codec.h"
#include "dataset/dataset_files.h"
#include "dataset/format_version.h"

namespace depot::dataset {

std::string label_image_name(double timestamp) {
  return std::string(kLabelFolder) + "/" + format_timestamp(timestamp) + ".png";
}

void write_label_list(const std::string& dataset_dir, const std::string& scenario_name,
                      const std::vector<double>& timestamps) {
  std::string text = "# instance label images (16-bit instance ids, 0 = none)\n" +
                     file_header_line(scenario_name) + "# timestamp filename\n";
  for (double t : timestamps) text += format_timestamp(t) + " " + label_image_name(t) + "\n";
  write_text_file_atomic(dataset_file(dataset_dir, kLabelListFile), text);
}

size_t write_label_image(const std::string& dataset_dir, double timestamp, const cv::Mat& labels,
                         int compression_level) {
  return write_png(dataset_file(dataset_dir, label_image_name(timestamp)), labels, PngKind::kLabels,
                   compression_level);
}

bool has_label_list(const std::string& dataset_dir) {
  return std::filesystem::is_regular_file(dataset_file(dataset_dir, kLabelListFile));
}

std::vector<StampedFile> read_label_list(const std::string& dataset_dir) {
  check_format_version(dataset_dir);
  const std::string path = dataset_file(dataset_dir, kLabelListFile);
  if (!std::filesystem::is_regular_file(path))
    fail(path, "cannot open file (the instance label images; not a simulated dataset?)");
  return read_file_list(path);
}

cv::Mat read_label_image(const std::string& dataset_dir, const std::string& relative_path) {
  const std::string path = dataset_file(dataset_dir, relative_path);
  cv::Mat labels = read_image(path, ImageRead::kUnchanged);
  if (labels.type() != CV_16UC1) fail(path, "label image is not 16-bit single-channel");
  return labels;
}

}  // namespace depot::dataset
