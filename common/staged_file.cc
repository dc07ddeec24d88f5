#include "common/staged_file.h"

#include <unistd.h>

#include <filesystem>

#include "common/error.h"
#include "common/staged_names.h"
#include "common/stale_partials.h"

namespace fs = std::filesystem;

namespace depot {

namespace {

std::string staging_prefix(const fs::path& p) {
  return "." + p.filename().string() + ".partial-";
}

// Why `final_path` cannot be written, or "" when it looks writable.
std::string output_problem(const std::string& final_path) {
  if (final_path.empty()) return "empty output path";
  const fs::path p(final_path);
  std::error_code ec;
  if (!p.has_filename() || fs::is_directory(p, ec)) return "is a folder; give a file name";
  const fs::path folder = p.has_parent_path() ? p.parent_path() : fs::path(".");
  if (!fs::is_directory(folder, ec)) return "folder " + folder.string() + " does not exist";
  if (::access(folder.c_str(), W_OK) != 0) return "folder " + folder.string() + " is not writable";
  if (fs::exists(p, ec) && !fs::is_regular_file(p, ec)) return "exists and is not a regular file";
  return "";
}

}  // namespace

void check_output_file(const std::string& final_path) {
  const std::string problem = output_problem(final_path);
  if (!problem.empty()) fail(final_path, problem);
  // access() says yes to root on a read-only file system: try for real.
  StagedFile probe(final_path);
}

StagedFile::StagedFile(const std::string& final_path) : final_path_(final_path) {
  const std::string problem = output_problem(final_path);
  if (!problem.empty()) fail(final_path, problem);
  const fs::path p(final_path);
  remove_stale_partials(p.has_parent_path() ? p.parent_path().string() : ".", staging_prefix(p));
  staging_path_ = (p.parent_path() / (staging_prefix(p) + std::to_string(::getpid()))).string();
  remember_staged_name(staging_path_, final_path_);
  out_.open(staging_path_, std::ios::binary);
  if (!out_) fail(final_path_, "cannot write file (is the folder there and writable?)");
}

StagedFile::~StagedFile() {
  if (committed_) return;
  out_.close();
  std::error_code ec;
  fs::remove(staging_path_, ec);
}

void StagedFile::commit() {
  out_.flush();
  const bool written = static_cast<bool>(out_);
  out_.close();
  if (!written) fail(final_path_, "write failed (disk full?)");
  std::error_code ec;
  fs::rename(staging_path_, final_path_, ec);
  if (ec) fail(final_path_, "cannot move the finished file into place: " + ec.message());
  committed_ = true;
}

}  // namespace depot
