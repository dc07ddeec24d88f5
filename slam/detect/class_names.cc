#include "slam/detect/class_names.h"

#include <algorithm>
#include <fstream>

#include "common/error.h"

namespace depot::slam {
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

std::vector<bool> wanted_classes(const std::vector<std::string>& names,
                                 const std::vector<std::string>& wanted,
                                 const std::string& names_path) {
  if (wanted.empty()) return std::vector<bool>(names.size(), true);
  std::vector<bool> keep(names.size(), false);
  for (const std::string& w : wanted) {
    const auto it = std::find(names.begin(), names.end(), w);
    if (it == names.end())
      fail(names_path, "wanted class '" + w + "' is not one of the model's " +
                           std::to_string(names.size()) + " classes");
    keep[static_cast<size_t>(it - names.begin())] = true;
  }
  return keep;
}

}  // namespace depot::slam
