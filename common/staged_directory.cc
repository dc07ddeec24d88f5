#include "common/staged_directory.h"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <mutex>
#include <set>

#include "common/error.h"
#include "common/staged_names.h"
#include "common/stale_partials.h"

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

fs::path absolute_target(const std::string& path) {
  if (path.empty()) fail("output", "empty output path");
  std::error_code ec;
  fs::path target = fs::absolute(path, ec);
  if (ec) fail(path, "invalid output path");
  target = target.lexically_normal();
  if (!target.has_filename()) target = target.parent_path();
  return target;
}

// True when `inner` is `outer` or lies inside it (symbolic links resolved).
bool contains(const fs::path& outer, const fs::path& inner) {
  std::error_code ec;
  const fs::path a = fs::weakly_canonical(outer, ec);
  const fs::path b = fs::weakly_canonical(inner, ec);
  auto ai = a.begin(), bi = b.begin();
  for (; ai != a.end(); ++ai, ++bi) {
    if (bi == b.end() || *ai != *bi) return false;
  }
  return true;
}

// A process killed inside commit() may have moved the old output aside
// ("OUT.replaced-<pid>") without moving the new one in: put the old one back
// when OUT is missing, otherwise it was replaced and goes.
void restore_or_remove_stale_replaced(const fs::path& target) {
  const std::string prefix = target.filename().string() + ".replaced-";
  std::error_code ec;
  for (fs::directory_iterator it(target.parent_path(), ec), end; !ec && it != end;
       it.increment(ec)) {
    const long pid = staged_entry_pid(it->path().filename().string(), prefix);
    if (pid < 0 || process_is_alive(pid)) continue;
    std::error_code move_error;
    if (!fs::exists(target, move_error)) {
      fs::rename(it->path(), target, move_error);
      return;
    }
  }
  remove_stale_partials(target.parent_path().string(), prefix);
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

void check_replaceable(const std::string& folder, const OutputKind& kind, bool overwrite) {
  const fs::path target = absolute_target(folder);
  std::error_code ec;
  if (!fs::exists(target, ec)) return;
  if (!fs::is_directory(target, ec)) fail(folder, "exists and is not a folder");
  // Replacing it would pull the folder from under the user's shell.
  if (contains(target, fs::current_path(ec)))
    fail(folder, "is the current folder or contains it; write the output elsewhere");
  if (fs::is_empty(target, ec)) return;
  if (!overwrite) fail(folder, "output folder exists and is not empty (use --overwrite)");
  if (!fs::is_regular_file(target / kind.marker, ec))
    fail(folder, "is not a " + kind.name + " written by depot (no " + kind.marker +
                     "); refusing to replace it, choose another output");
  for (fs::directory_iterator it(target, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (std::find(kind.entries.begin(), kind.entries.end(), name) == kind.entries.end())
      fail(folder, "holds '" + name + "', which depot did not write; refusing to replace it");
  }
  if (ec) fail(folder, "cannot list the existing output folder: " + ec.message());
}

StagedDirectory::StagedDirectory(const std::string& final_path, const OutputKind& kind,
                                 bool overwrite)
    : final_path_(final_path), kind_(kind), overwrite_(overwrite) {
  const fs::path target = absolute_target(final_path);
  check_replaceable(final_path, kind_, overwrite_);
  std::error_code ec;
  fs::path parent = target.parent_path();
  fs::create_directories(parent, ec);
  if (ec || !fs::is_directory(parent)) fail(final_path, "cannot create parent folder");
  if (access(parent.c_str(), W_OK) != 0) fail(final_path, "parent folder is not writable");
  final_path_ = target.string();
  const std::string prefix = target.filename().string() + ".partial-";
  remove_stale_partials(parent.string(), prefix);
  restore_or_remove_stale_replaced(target);
  staging_path_ = (parent / (prefix + std::to_string(getpid()))).string();
  fs::remove_all(staging_path_, ec);
  if (!fs::create_directory(staging_path_, ec) || ec) {
    fail(final_path, "cannot create output folder");
  }
  remember_staged_name(staging_path_, final_path_);
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
  // The folder may have changed while we worked: check it again.
  check_replaceable(final_path_, kind_, overwrite_);
  std::string aside;
  if (fs::exists(final_path_, ec)) {
    aside = final_path_ + ".replaced-" + std::to_string(getpid());
    fs::remove_all(aside, ec);
    fs::rename(final_path_, aside, ec);
    if (ec) fail(final_path_, "cannot move the existing output aside: " + ec.message());
  }
  fs::rename(staging_path_, final_path_, ec);
  if (ec) {
    std::error_code restore;
    if (!aside.empty()) fs::rename(aside, final_path_, restore);
    fail(final_path_, "cannot move finished output into place: " + ec.message());
  }
  committed_ = true;
  if (!aside.empty()) fs::remove_all(aside, ec);
}

}  // namespace depot
