#pragma once
// An output folder that appears only when complete: work happens in a hidden
// sibling ("OUT.partial-<pid>") that commit() renames to OUT. If the job fails
// or is interrupted before commit, the partial folder is removed, so a user
// never finds a half-written dataset under OUT. Partial folders that a killed
// process (SIGKILL, power loss) left beside OUT are removed by the next run to
// the same OUT; those of live processes are left alone.
//
// Overwriting never deletes what a user wrote: an existing OUT is replaced only
// when it is an output of the same kind (it holds the kind's marker file and
// nothing but the kind's own entries), and only once the new output is
// complete. Anything else is refused before any work starts.
#include <string>
#include <vector>

namespace depot {

// What one kind of output folder holds, so that an existing folder can be
// recognised as ours before it is replaced.
struct OutputKind {
  std::string name;                  // for messages, e.g. "dataset"
  std::string marker;                // a file every such folder has, e.g. "info.json"
  std::vector<std::string> entries;  // every top-level name such a folder may hold
};

class StagedDirectory {
 public:
  // Fails (depot::Error naming `final_path`) when OUT exists and is not empty
  // and `overwrite` is false, when OUT is not an output of `kind` (then even
  // with `overwrite`), when OUT is the current folder or contains it, or when
  // the parent is not writable.
  StagedDirectory(const std::string& final_path, const OutputKind& kind, bool overwrite);
  ~StagedDirectory();
  StagedDirectory(const StagedDirectory&) = delete;
  StagedDirectory& operator=(const StagedDirectory&) = delete;

  const std::string& path() const { return staging_path_; }
  const std::string& final_path() const { return final_path_; }
  // Moves the finished folder into place; an existing OUT (checked again) is
  // moved aside first and removed only after the new folder is in place.
  void commit();

 private:
  std::string final_path_;
  std::string staging_path_;
  OutputKind kind_;
  bool overwrite_;
  bool committed_ = false;
};

// Throws depot::Error unless `folder` is missing, empty, or an output of
// `kind` that may be replaced (see above); `overwrite` false refuses any
// non-empty folder.
void check_replaceable(const std::string& folder, const OutputKind& kind, bool overwrite);

// Removes every staged (uncommitted) folder of this process; for fatal-error
// paths that cannot unwind (e.g. a C library's error callback).
void remove_all_staged_directories();

}  // namespace depot
