#include "sim/scenario/class_table.h"

#include <yaml-cpp/yaml.h>

#include "common/error.h"

namespace depot::sim {

const char* category_name(Category c) {
  switch (c) {
    case Category::kStatic:
      return "static";
    case Category::kPotentiallyDynamic:
      return "potentially_dynamic";
    case Category::kDynamic:
      return "dynamic";
  }
  return "static";
}

ClassTable ClassTable::load(const std::string& path) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    fail(path, "cannot open class table");
  } catch (const YAML::Exception& e) {
    fail(path, "line " + std::to_string(e.mark.line + 1) + ": " + e.msg);
  }
  ClassTable table;
  YAML::Node classes = root["classes"];
  if (!classes || !classes.IsMap()) fail(path, "expected a map 'classes: {name: {...}}'");
  for (const auto& entry : classes) {
    ObjectClass c;
    c.name = entry.first.as<std::string>();
    std::string cat = entry.second["category"].as<std::string>("static");
    if (cat == "dynamic") {
      c.category = Category::kDynamic;
    } else if (cat == "potentially_dynamic") {
      c.category = Category::kPotentiallyDynamic;
    } else if (cat == "static") {
      c.category = Category::kStatic;
    } else {
      fail(path, "class '" + c.name + "': unknown category '" + cat +
                     "' (expected dynamic, potentially_dynamic or static)");
    }
    c.detectable = entry.second["detectable"].as<bool>(false);
    table.classes_.push_back(c);
  }
  return table;
}

bool ClassTable::contains(const std::string& name) const {
  for (const auto& c : classes_)
    if (c.name == name) return true;
  return false;
}

const ObjectClass& ClassTable::get(const std::string& name, const std::string& context) const {
  for (const auto& c : classes_)
    if (c.name == name) return c;
  fail(context, "unknown class '" + name + "'");
}

int ClassTable::yolo_index(const std::string& name) const {
  int index = 0;
  for (const auto& c : classes_) {
    if (!c.detectable) continue;
    if (c.name == name) return index;
    ++index;
  }
  return -1;
}

std::vector<std::string> ClassTable::yolo_names() const {
  std::vector<std::string> names;
  for (const auto& c : classes_)
    if (c.detectable) names.push_back(c.name);
  return names;
}

}  // namespace depot::sim
