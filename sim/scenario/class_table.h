#pragma once
// Object classes of the depot and their a-priori motion category (PAPER.md,
// Table 1). Loaded from scenes/classes.yaml so the table is configuration.
#include <string>
#include <vector>

namespace depot::sim {

enum class Category { kStatic, kPotentiallyDynamic, kDynamic };

const char* category_name(Category c);

struct ObjectClass {
  std::string name;  // e.g. "person"
  Category category = Category::kStatic;
  bool detectable = false;  // gets ground-truth boxes and a YOLO class index
};

class ClassTable {
 public:
  static ClassTable load(const std::string& path);

  // Throws depot::Error naming `context` for an unknown class.
  const ObjectClass& get(const std::string& name, const std::string& context) const;
  bool contains(const std::string& name) const;
  // Index among detectable classes (the YOLO class id), or -1.
  int yolo_index(const std::string& name) const;
  std::vector<std::string> yolo_names() const;
  const std::vector<ObjectClass>& classes() const { return classes_; }

 private:
  std::vector<ObjectClass> classes_;
};

}  // namespace depot::sim
