#include "dataset/dataset_files.h"

#include <fmt/format.h>

#include <filesystem>

namespace depot::dataset {

std::string dataset_file(const std::string& dataset_dir, const std::string& name) {
  return (std::filesystem::path(dataset_dir) / name).string();
}

std::string format_timestamp(double t) {
  return fmt::format("{:.6f}", t);
}

std::string file_header_line(const std::string& scenario_name) {
  return "# file: '" + scenario_name + "' (depot-slam simulator)\n";
}

}  // namespace depot::dataset
