#include "common/staged_file.h"

#include <unistd.h>

#include <filesystem>

#include "common/error.h"

namespace fs = std::filesystem;

namespace depot {

StagedFile::StagedFile(const std::string& final_path) : final_path_(final_path) {
  const fs::path p(final_path);
  staging_path_ =
      (p.parent_path() / ("." + p.filename().string() + ".partial-" + std::to_string(::getpid())))
          .string();
  out_.open(staging_path_);
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
