#pragma once
// An output folder that appears only when complete: work happens in a hidden
// sibling ("OUT.partial-<pid>") that commit() renames to OUT. If the job fails
// or is interrupted before commit, the partial folder is removed, so a user
// never finds a half-written dataset under OUT.
#include <string>

namespace depot {

class StagedDirectory {
 public:
  // Fails (depot::Error naming `final_path`) when OUT exists and is not empty
  // and `overwrite` is false, or when the parent is not writable.
  StagedDirectory(const std::string& final_path, bool overwrite);
  ~StagedDirectory();
  StagedDirectory(const StagedDirectory&) = delete;
  StagedDirectory& operator=(const StagedDirectory&) = delete;

  const std::string& path() const { return staging_path_; }
  const std::string& final_path() const { return final_path_; }
  void commit();

 private:
  std::string final_path_;
  std::string staging_path_;
  bool overwrite_;
  bool committed_ = false;
};

// Removes every staged (uncommitted) folder of this process; for fatal-error
// paths that cannot unwind (e.g. a C library's error callback).
void remove_all_staged_directories();

}  // namespace depot
