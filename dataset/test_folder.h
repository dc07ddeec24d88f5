#pragma once
// Test helper (header-only): fresh folders for hand-made datasets, inside a
// folder of this test process that is removed when it exits.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace depot::dataset::testing {

// A new empty folder.
inline std::string new_test_folder() {
  static const std::filesystem::path root =
      std::filesystem::temp_directory_path() / ("depot_dataset_test_" + std::to_string(::getpid()));
  static const struct Cleanup {
    ~Cleanup() { std::filesystem::remove_all(root); }
  } cleanup;
  static int count = 0;
  const std::filesystem::path dir = root / std::to_string(count++);
  std::filesystem::create_directories(dir);
  return dir.string();
}

// Writes `text` to `dir`/`name`.
inline void write_text(const std::string& dir, const std::string& name, const std::string& text) {
  std::ofstream(std::filesystem::path(dir) / name, std::ios::binary) << text;
}

// The bytes of `dir`/`name`.
inline std::string read_text(const std::string& dir, const std::string& name) {
  std::ifstream in(std::filesystem::path(dir) / name, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace depot::dataset::testing
