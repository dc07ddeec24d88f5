#include "dataset/class_list.h"

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "common/error.h"
#include "common/tum_io.h"
#include "dataset/dataset_files.h"

namespace depot::dataset {
namespace {

std::string trim(const std::string& s) {
  const char* ws = " \t\r\n\f\v";
  const auto b = s.find_first_not_of(ws);
  if (b == std::string::npos) return {};
  return s.substr(b, s.find_last_not_of(ws) - b + 1);
}

}  // namespace

std::vector<std::string> load_class_names(const std::string& path) {
  std::ifstream in(path);
  if (!in) fail(path, "cannot open class names file");
  std::vector<std::string> names;
  int blank_line = 0;  // first blank line seen so far (1-based), 0 if none
  int line_no = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    std::string name = trim(line);
    if (name.empty()) {
      if (blank_line == 0) blank_line = line_no;
      continue;
    }
    // A blank line followed by a name would shift every later class index.
    if (blank_line != 0)
      fail(path + ":" + std::to_string(blank_line), "blank line before a class name");
    names.push_back(std::move(name));
  }
  if (names.empty()) fail(path, "class names file lists no class");
  return names;
}

std::vector<std::string> read_dataset_classes(const std::string& dataset_dir) {
  const std::string path = dataset_file(dataset_dir, kClassesFile);
  if (!std::filesystem::exists(path)) fail(path, "missing (the detectable classes, one a line)");
  std::vector<std::string> classes = load_class_names(path);
  for (size_t i = 0; i < classes.size(); ++i)
    if (std::find(classes.begin(), classes.begin() + static_cast<long>(i), classes[i]) !=
        classes.begin() + static_cast<long>(i))
      fail(path, "class '" + classes[i] + "' is listed twice");
  return classes;
}

void write_dataset_classes(const std::string& dataset_dir, const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& n : names) text += n + "\n";
  write_text_file_atomic(dataset_file(dataset_dir, kClassesFile), text);
}

}  // namespace depot::dataset
