#pragma once
// An output file that appears only when complete: it is written under a
// hidden temporary name beside it ("name.partial-<pid>") that commit()
// renames into place. A run that fails or is interrupted before commit
// leaves no file, half-written or temporary.
#include <fstream>
#include <string>

namespace depot {

class StagedFile {
 public:
  // Throws depot::Error naming `final_path` when it cannot be written.
  explicit StagedFile(const std::string& final_path);
  ~StagedFile();
  StagedFile(const StagedFile&) = delete;
  StagedFile& operator=(const StagedFile&) = delete;

  std::ofstream& stream() { return out_; }
  const std::string& final_path() const { return final_path_; }
  // Flushes, closes and renames; throws depot::Error on a write failure.
  void commit();

 private:
  std::string final_path_;
  std::string staging_path_;
  std::ofstream out_;
  bool committed_ = false;
};

// Checks, before a long job starts, that `final_path` can be written at its
// end: not a folder, its folder exists and takes a new file. Throws
// depot::Error naming the path and the problem; leaves nothing behind.
void check_output_file(const std::string& final_path);

}  // namespace depot
