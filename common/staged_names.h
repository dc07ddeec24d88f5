#pragma once
// Staged outputs (staged_file.h, staged_directory.h) are written under a
// temporary name that is gone once a failure has unwound. An error met while
// writing one names that temporary path; each staged output records its pair
// here so the error line a user reads names the final path instead.
// Thread-safe (one process-wide table behind a mutex).
#include <string>

namespace depot {

// Records that `staging_path` is written for `final_path`.
void remember_staged_name(const std::string& staging_path, const std::string& final_path);

// `message` with every recorded staging path replaced by its final path.
std::string with_final_names(std::string message);

}  // namespace depot
