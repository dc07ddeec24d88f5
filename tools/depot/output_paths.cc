#include "tools/depot/output_paths.h"

#include <sys/stat.h>

#include <filesystem>

#include "tools/depot/cli_errors.h"

namespace fs = std::filesystem;

namespace depot::cli {
namespace {

bool inside(const std::string& path, const std::string& folder) {
  return path.size() > folder.size() && path.compare(0, folder.size(), folder) == 0 &&
         (folder.back() == '/' || path[folder.size()] == '/');
}

}  // namespace

void OutputPaths::add_file(const std::string& role, const std::string& path) {
  add(Kind::kFile, role, path);
}

void OutputPaths::add_folder(const std::string& role, const std::string& path) {
  add(Kind::kFolder, role, path);
}

void OutputPaths::add_input(const std::string& role, const std::string& path) {
  add(Kind::kInput, role, path);
}

void OutputPaths::add_input_folder(const std::string& role, const std::string& path) {
  add(Kind::kInputFolder, role, path);
}

void OutputPaths::add(Kind kind, const std::string& role, const std::string& path) {
  if (path.empty()) return;
  Entry e;
  e.role = role;
  e.path = path;
  e.kind = kind;
  std::error_code ec;
  // weakly_canonical follows every link of the part that exists, so "a.txt"
  // and "./link-to-here/a.txt" resolve alike even before a.txt is written.
  const fs::path resolved = fs::weakly_canonical(fs::absolute(path, ec), ec);
  e.resolved = (ec ? fs::absolute(path) : resolved).lexically_normal().string();
  while (e.resolved.size() > 1 && e.resolved.back() == '/') e.resolved.pop_back();
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    e.exists = true;
    e.is_folder = S_ISDIR(st.st_mode);
    e.device = st.st_dev;
    e.inode = st.st_ino;
  }
  entries_.push_back(e);
}

void OutputPaths::check() const {
  for (size_t i = 0; i < entries_.size(); ++i) {
    for (size_t j = i + 1; j < entries_.size(); ++j) {
      const Entry& a = entries_[i];
      const Entry& b = entries_[j];
      const auto is_input = [](const Entry& e) {
        return e.kind == Kind::kInput || e.kind == Kind::kInputFolder;
      };
      if (is_input(a) && is_input(b)) continue;
      const Entry* read_folder = a.kind == Kind::kInputFolder   ? &a
                                 : b.kind == Kind::kInputFolder ? &b
                                                                : nullptr;
      if (read_folder) {
        const Entry& out = read_folder == &a ? b : a;
        // An existing folder as a file output is refused by the writability
        // check ("is a folder"), in its own words.
        if (out.exists && !out.is_folder && inside(out.resolved, read_folder->resolved))
          fail_usage(out.role, "would write over " + out.path + ", a file of " + read_folder->role +
                                   " it reads");
        continue;
      }
      const bool same = a.resolved == b.resolved ||
                        (a.exists && b.exists && a.device == b.device && a.inode == b.inode);
      if (same) {
        const Entry& input = is_input(a) ? a : b;
        const Entry& other = is_input(a) ? b : a;
        if (is_input(a) || is_input(b))
          fail_usage(other.role,
                     "would write over the file " + input.role + " reads (" + other.path + ")");
        fail_usage(b.role, "is the same file as " + a.role + " (" + b.path +
                               "); each output needs its own path");
      }
      const Entry* folder = a.kind == Kind::kFolder ? &a : b.kind == Kind::kFolder ? &b : nullptr;
      const Entry* other = folder == &a ? &b : &a;
      if (folder && inside(other->resolved, folder->resolved))
        fail_usage(other->role, other->path + " lies inside the folder " + folder->role +
                                    " writes (" + folder->path + "), which it replaces");
    }
  }
}

}  // namespace depot::cli
