#pragma once
// One rule for a command's outputs: every path it will write (and every file
// it reads) is collected before any work starts, and two that are one file,
// by name, through symbolic links or as hard links of one inode, or a file
// inside a folder the command replaces, are a command-line error. Without it
// `slam run D -o a.txt --save-map a.txt` would end with the map written over
// the trajectory (or the other way round).
#include <string>
#include <vector>

namespace depot::cli {

class OutputPaths {
 public:
  // `role` names the option on the error line, e.g. "--save-map" or
  // "the states file of -o". Empty paths are ignored.
  void add_file(const std::string& role, const std::string& path);
  // A folder the command writes whole (replaced when it exists): nothing else
  // may be written inside it.
  void add_folder(const std::string& role, const std::string& path);
  // A file the command reads: no output may be it.
  void add_input(const std::string& role, const std::string& path);
  // A folder the command reads (a dataset): no output may be a file that
  // already exists inside it (new files beside its own are fine).
  void add_input_folder(const std::string& role, const std::string& path);

  // Throws a command-line error (exit 2) naming both roles and the path
  // when two entries are one file, or a file sits inside an output folder.
  void check() const;

 private:
  enum class Kind { kFile, kFolder, kInput, kInputFolder };
  struct Entry {
    std::string role;
    std::string path;      // as given
    std::string resolved;  // absolute, links and ".." resolved as far as it exists
    bool exists = false;
    bool is_folder = false;
    unsigned long long device = 0, inode = 0;
    Kind kind = Kind::kFile;
  };
  void add(Kind kind, const std::string& role, const std::string& path);
  std::vector<Entry> entries_;
};

}  // namespace depot::cli
