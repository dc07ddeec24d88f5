#pragma once
// Command-line overrides of YAML settings, "a.b.c=value": a sweep or a user
// changes one key of a scenario or detector file without editing it. The
// value is parsed as YAML, so numbers, booleans and lists keep their type.
#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

namespace depot {

struct YamlOverride {
  std::string key;  // dotted path, e.g. "sensor.disparity_noise"
  std::string value;
};

// Parses "key=value". Throws Error("<where>: ...") when there is no '=', the
// key is empty or has an empty part ("a..b"), or the value is empty.
YamlOverride parse_yaml_override(const std::string& text, const std::string& where);

// Sets root[a][b][c] = value, creating maps on the way. Throws
// Error("<where>: ...") when a part of the path is not a map or the value is
// not valid YAML.
void apply_yaml_override(YAML::Node& root, const YamlOverride& override_, const std::string& where);

// A map node holding all overrides (for settings read from a node).
YAML::Node overrides_to_node(const std::vector<YamlOverride>& overrides, const std::string& where);

}  // namespace depot
