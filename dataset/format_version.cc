#include "dataset/format_version.h"

#include <filesystem>

#include "common/error.h"
#include "dataset/dataset_files.h"
#include "dataset/json_file.h"

namespace depot::dataset {

int checked_format_version(const nlohmann::json& info, const std::string& info_path) {
  if (!info.is_object()) fail(info_path, "not a dataset's info file (not a JSON object)");
  const auto it = info.find("format_version");
  if (it == info.end()) return 1;
  if (!it->is_number_integer() || it->get<long long>() < 1)
    fail(info_path, "format_version " + it->dump() + " is not a whole number >= 1");
  const long long version = it->get<long long>();
  if (version > kFormatVersion)
    fail(info_path, "format_version " + std::to_string(version) +
                        " is newer than this program reads (up to " +
                        std::to_string(kFormatVersion) + "): update depot-slam");
  return static_cast<int>(version);
}

void check_format_version(const std::string& dataset_dir) {
  const std::string path = dataset_file(dataset_dir, kInfoFile);
  if (!std::filesystem::exists(path)) return;
  checked_format_version(read_json_file(path, "the dataset's info"), path);
}

}  // namespace depot::dataset
