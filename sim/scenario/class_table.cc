#include "sim/scenario/class_table.h"

#include <yaml-cpp/yaml.h>

#include "common/error.h"
#include "common/yaml_fields.h"
#include "common/yaml_file.h"

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
  const YAML::Node root = load_yaml_file(path, "class table");
  if (!root.IsMap() || !root["classes"] || !root["classes"].IsMap())
    fail(path, "expected a map 'classes: {name: {...}}'");
  const YamlSource source{path, {}};
  ClassTable table;
  for (const auto& entry : root["classes"]) {
    ObjectClass c;
    c.name = yaml_value<std::string>(entry.first, "class name", source);
    const YamlFields fields(entry.second, source, "class '" + c.name + "'");
    fields.allow_only({"category", "detectable"});
    const std::string cat = fields.str("category", "static");
    if (cat == "dynamic") {
      c.category = Category::kDynamic;
    } else if (cat == "potentially_dynamic") {
      c.category = Category::kPotentiallyDynamic;
    } else if (cat == "static") {
      c.category = Category::kStatic;
    } else {
      fail(fields.where(fields.node("category")),
           "class '" + c.name + "': unknown category '" + printable(cat) +
               "' (expected dynamic, potentially_dynamic or static)");
    }
    c.detectable = fields.flag("detectable", false);
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
