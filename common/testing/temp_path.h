#pragma once
// Paths for a test process's files: one new folder per process under the
// system temp dir, made by mkdtemp (so it is never the leftover of an
// earlier process with the same id) and removed with everything in it when
// the process exits (set DEPOT_KEEP_TEST_FILES to keep it for a post-mortem),
// so test runs do not fill the temporary folder. For a folder that lives
// only as long as one test, use ScratchFolder (scratch_folder.h).
#include <stdlib.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <stdexcept>
#include <string>

namespace depot::testkit {

namespace detail {

inline std::filesystem::path& process_folder_path() {
  static std::filesystem::path root;
  return root;
}

inline void remove_process_folder() {
  std::error_code ec;
  std::filesystem::remove_all(process_folder_path(), ec);
}

}  // namespace detail

// This process's test folder (made on first use).
inline const std::filesystem::path& process_folder() {
  static std::once_flag once;
  std::call_once(once, [] {
    std::string pattern = (std::filesystem::temp_directory_path() / "depot_test_XXXXXX").string();
    if (!::mkdtemp(pattern.data()))
      throw std::runtime_error("cannot create a test folder like " + pattern);
    detail::process_folder_path() = pattern;
    if (!std::getenv("DEPOT_KEEP_TEST_FILES")) std::atexit(detail::remove_process_folder);
  });
  return detail::process_folder_path();
}

// A new path in the process's folder, named after `tag` and never handed out
// before (nothing is created there).
inline std::string temp_path(const std::string& tag) {
  static std::atomic<int> counter{0};
  return (process_folder() / (tag + "_" + std::to_string(counter++))).string();
}

}  // namespace depot::testkit
