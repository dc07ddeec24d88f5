#pragma once
// Class-name lists of detection models (Darknet's coco.names format: one
// name a line, line i is class i).
#include <string>
#include <vector>

namespace depot::slam {

// Reads a class-names file. Surrounding white space (and a Windows '\r') is
// trimmed and trailing blank lines are ignored. Throws depot::Error naming the
// file when it cannot be opened, lists no class, or has a blank line before a
// name (which would shift every later class index).
std::vector<std::string> load_class_names(const std::string& path);

// Which of `names` to keep: all when `wanted` is empty, else exactly the
// listed ones. Throws depot::Error "<names_path>: ..." for a wanted class that
// is not in `names`.
std::vector<bool> wanted_classes(const std::vector<std::string>& names,
                                 const std::vector<std::string>& wanted,
                                 const std::string& names_path);

}  // namespace depot::slam
