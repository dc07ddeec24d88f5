#pragma once
// Test helper (header-only): small text files in a folder of this test
// process, removed when it exits.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace depot::eval::testing {

// Writes `text` to `name` in the process's scratch folder; returns its path.
inline std::string write_test_file(const std::string& name, const std::string& text) {
  static const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("depot_eval_test_" + std::to_string(::getpid()));
  static const struct Cleanup {
    ~Cleanup() { std::filesystem::remove_all(dir); }
  } cleanup;
  std::filesystem::create_directories(dir);
  const std::string path = (dir / name).string();
  std::ofstream(path) << text;
  return path;
}

}  // namespace depot::eval::testing
