#include "slam/reject/apriori_classes.h"

#include <yaml-cpp/yaml.h>

#include "common/error.h"
#include "common/yaml_file.h"

namespace depot::slam {

AprioriClasses::AprioriClasses(std::set<std::string> dynamic,
                               std::set<std::string> potentially_dynamic)
    : dynamic_(std::move(dynamic)), potential_(std::move(potentially_dynamic)) {}

AprioriClasses AprioriClasses::load(const std::string& path) {
  YAML::Node root = load_yaml_file(path, "class table");
  if (!root.IsMap())
    fail(path, "class table must be a map with 'dynamic' and 'potentially_dynamic' lists");
  AprioriClasses table;
  for (const auto& kv : root) {
    const std::string key = kv.first.as<std::string>();
    std::set<std::string>* target = key == "dynamic"               ? &table.dynamic_
                                    : key == "potentially_dynamic" ? &table.potential_
                                                                   : nullptr;
    if (!target)
      fail(path + ":" + std::to_string(kv.first.Mark().line + 1),
           "unknown key '" + key +
               "' (expected dynamic, potentially_dynamic; other classes are static)");
    if (!kv.second.IsSequence()) fail(path, "'" + key + "' must be a list of class names");
    for (const auto& n : kv.second) target->insert(n.as<std::string>());
  }
  for (const auto& c : table.dynamic_)
    if (table.potential_.count(c))
      fail(path, "class '" + c + "' is listed as both dynamic and potentially dynamic");
  if (table.dynamic_.empty()) fail(path, "no dynamic classes");
  return table;
}

MotionClass AprioriClasses::classify(const std::string& name) const {
  if (dynamic_.count(name)) return MotionClass::kDynamic;
  if (potential_.count(name)) return MotionClass::kPotentiallyDynamic;
  return MotionClass::kStatic;
}

void AprioriClasses::check_against(const std::vector<std::string>& detector_classes,
                                   const std::string& table_name,
                                   const std::string& detector_name) const {
  std::set<std::string> known(detector_classes.begin(), detector_classes.end());
  for (const auto* list : {&dynamic_, &potential_})
    for (const auto& c : *list)
      if (!known.count(c))
        fail(table_name,
             "unknown class '" + c + "': the " + detector_name + " detector has no such class");
}

}  // namespace depot::slam
