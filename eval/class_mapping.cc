#include "eval/class_mapping.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>

#include "common/error.h"
#include "common/yaml_file.h"

namespace depot::eval {
namespace {

int line_of(const YAML::Node& n) {
  return n.Mark().line + 1;
}

std::string name_of(const std::string& path, const YAML::Node& n, const char* what) {
  if (!n.IsScalar() || n.Scalar().empty())
    fail(yaml_where(path, n), std::string(what) + " must be a class name");
  return n.Scalar();
}

bool contains(const std::vector<std::string>& v, const std::string& s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const std::string& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

}  // namespace

ClassMapping ClassMapping::load(const std::string& path) {
  const YAML::Node root = load_yaml_file(path, "class mapping");
  if (!root.IsMap()) fail(path, "class mapping must be a YAML map (keys: map, any_animal)");
  ClassMapping m;
  m.path_ = path;
  check_known_keys(root, {"map", "any_animal"}, path);
  if (const YAML::Node map = root["map"]) {
    if (!map.IsMap()) fail(yaml_where(path, map), "'map' must map detector labels to classes");
    for (const auto& kv : map)
      m.map_.push_back({name_of(path, kv.first, "a detector label"),
                        name_of(path, kv.second, "a mapped class"), line_of(kv.second)});
  }
  if (const YAML::Node animal = root["any_animal"]) {
    if (!animal.IsMap())
      fail(yaml_where(path, animal), "'any_animal' must have 'classes' and 'labels'");
    check_known_keys(animal, {"classes", "labels"}, path);
    for (const auto& kv : animal)
      if (!kv.second.IsSequence())
        fail(yaml_where(path, kv.second),
             "'any_animal: " + kv.first.Scalar() + "' must be a list of names");
    for (const YAML::Node& n : animal["classes"])
      m.animal_classes_.push_back({name_of(path, n, "an any_animal class"), line_of(n)});
    for (const YAML::Node& n : animal["labels"])
      m.animal_labels_.push_back(name_of(path, n, "an any_animal label"));
    if (m.animal_classes_.empty() != m.animal_labels_.empty())
      fail(yaml_where(path, animal), "'any_animal' needs both 'classes' and 'labels'");
  }
  return m;
}

std::string ClassMapping::class_of(const std::string& label) const {
  for (const Entry& e : map_)
    if (e.from == label) return e.to;
  return label;
}

bool ClassMapping::matches(const std::string& label, const std::string& truth_class) const {
  if (class_of(label) == truth_class) return true;
  const bool animal_class = std::any_of(animal_classes_.begin(), animal_classes_.end(),
                                        [&](const Named& c) { return c.name == truth_class; });
  return animal_class && contains(animal_labels_, label);
}

bool ClassMapping::reachable(const std::string& truth_class,
                             const std::vector<std::string>& labels) const {
  return std::any_of(labels.begin(), labels.end(),
                     [&](const std::string& l) { return matches(l, truth_class); });
}

bool ClassMapping::relevant(const std::string& label,
                            const std::vector<std::string>& classes) const {
  return std::any_of(classes.begin(), classes.end(),
                     [&](const std::string& c) { return matches(label, c); });
}

void ClassMapping::check_classes(const std::vector<std::string>& classes,
                                 const std::string& what) const {
  auto check = [&](const std::string& name, int line) {
    if (!contains(classes, name))
      fail(path_ + ":" + std::to_string(line),
           "class '" + name + "' is not a class of " + what + " (" + joined(classes) + ")");
  };
  for (const Entry& e : map_) check(e.to, e.line);
  for (const Named& c : animal_classes_) check(c.name, c.line);
}

}  // namespace depot::eval
