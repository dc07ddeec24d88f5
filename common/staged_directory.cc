#include "common/staged_directory.h"

#include <unistd.h>

#include <filesystem>
#include <mutex>
#include <set>

#include "common/error.h"

namespace fs = std::filesystem;

namespace depot {
namespace {

std::mutex& registry_mutex() {
  static std::mutex m;
  return m;
}
std::set<std::string>& registry() {
  static std::set<std::string> paths;
  return paths;
}

}  // namespace

void remove_all_staged_directories() {
  std::lock_guard<std::mutex> lock(registry_mutex());
  for (const auto& p : registry()) {
    std::error_code ec;
    fs::remove_all(p, ec);
  }
  registry().clear();
}

StagedDirectory::StagedDirectory(const std::string& final_path, bool overwrite)
    : final_path_(final_path), overwrite_(overwrite) {
  if (final_path.empty()) fail("output", "empty output path");
  std::error_code ec;
  fs::path target = fs::absolute(final_path, ec);
  if (ec) fail(final_path, "invalid output path");
  if (!target.has_filename()) target = target.parent_path();
  if (fs::exists(target, ec)) {
    if (!fs::is_directory(target, ec)) fail(final_path, "exists and is not a folder");
    if (!fs::is_empty(target, ec) && !overwrite_) {
      fail(final_path, "output folder exists and is not empty (use --overwrite)");
    }
  }
  fs::path parent = target.parent_path();
  fs::create_directories(parent, ec);
  if (ec || !fs::is_directory(parent)) fail(final_path, "cannot create parent folder");
  if (access(parent.c_str(), W_OK) != 0) fail(final_path, "parent folder is not writable");
  final_path_ = target.string();
  staging_path_ = final_path_ + ".partial-" + std::to_string(getpid());
  fs::remove_all(staging_path_, ec);
  if (!fs::create_directory(staging_path_, ec) || ec) {
    fail(final_path, "cannot create output folder");
  }
  std::lock_guard<std::mutex> lock(registry_mutex());
  registry().insert(staging_path_);
}

StagedDirectory::~StagedDirectory() {
  {
    std::lock_guard<std::mutex> lock(registry_mutex());
    registry().erase(staging_path_);
  }
  if (!committed_) {
    std::error_code ec;
    fs::remove_all(staging_path_, ec);
  }
}

void StagedDirectory::commit() {
  std::error_code ec;
  if (fs::exists(final_path_, ec)) {
    fs::remove_all(final_path_, ec);
    if (ec) fail(final_path_, "cannot replace existing output folder");
  }
  fs::rename(staging_path_, final_path_, ec);
  if (ec) fail(final_path_, "cannot move finished output into place: " + ec.message());
  committed_ = true;
}

}  // namespace depot
