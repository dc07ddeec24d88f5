#pragma once
// Class-name lists: one name a line, line i is class i. Detection models
// ship them (Darknet's coco.names), and a dataset's classes.txt lists its
// detectable classes in their YOLO index order (boxes_yolo/).
#include <string>
#include <vector>

namespace depot::dataset {

inline constexpr const char* kClassesFile = "classes.txt";

// Reads a class-names file. Surrounding white space (and a Windows '\r') is
// trimmed and trailing blank lines are ignored. Throws depot::Error naming the
// file when it cannot be opened, lists no class, or has a blank line before a
// name (which would shift every later class index).
std::vector<std::string> load_class_names(const std::string& path);

// A dataset's classes.txt: as load_class_names, and no class twice.
std::vector<std::string> read_dataset_classes(const std::string& dataset_dir);
void write_dataset_classes(const std::string& dataset_dir, const std::vector<std::string>& names);

}  // namespace depot::dataset
