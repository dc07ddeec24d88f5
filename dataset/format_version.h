#pragma once
// The version of the dataset format, written into info.json as
// "format_version". Readers check it before they read any truth file, so a
// dataset from a newer program fails with one clear line instead of being
// misread. Datasets written before the key existed are version 1.
#include <string>

#include <nlohmann/json.hpp>

namespace depot::dataset {

// What this program writes and the newest it reads. Raise it when a truth
// file changes in a way older readers would misread.
inline constexpr int kFormatVersion = 1;

// The version an info.json document states (1 when it states none). Throws
// depot::Error("<info_path>: ...") when it is not a whole number >= 1 or is
// newer than kFormatVersion.
int checked_format_version(const nlohmann::json& info, const std::string& info_path);

// Checks the version of the dataset in `dataset_dir` (its info.json; a
// folder without one, e.g. hand-made truth files, counts as version 1).
void check_format_version(const std::string& dataset_dir);

}  // namespace depot::dataset
