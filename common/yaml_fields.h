#pragma once
// The one typed reader of config files' YAML fields (scenarios, scene layouts,
// SLAM settings, detector, segmenter and simulated-detector configs): each
// field read with a fallback for when it is absent, a value of the wrong type
// or out of its range being one error line "<file>:<line>: <problem>".
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <initializer_list>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "common/error.h"
#include "common/number_text.h"

namespace depot {

// Where a config's values came from: a line of `file`, or a command-line
// override ("--set key=value"), whose value node has no line of its own.
struct YamlSource {
  std::string file;
  std::vector<std::pair<YAML::Node, std::string>> overrides;  // value node, option text

  // "<file>:<line>", the option text of an override, or "<file>" for a node
  // with no line (a map made by overrides alone).
  std::string where(const YAML::Node& node) const;
};

// A value node as a T, "bad value for '<key>'" where it is when it is not one
// (for values found by walking a map, e.g. a class -> rate table).
template <typename T>
T yaml_value(const YAML::Node& value, const std::string& key, const YamlSource& source) {
  try {
    return value.as<T>();
  } catch (const YAML::Exception&) {
    fail(source.where(value), "bad value for '" + key + "'");
  }
}

// The fields of one YAML map.
class YamlFields {
 public:
  // An absent `map` reads as an empty one (every field takes its fallback);
  // one that is present but not a map fails "<what> must be a map".
  YamlFields(const YAML::Node& map, YamlSource source, const std::string& what);
  YamlFields(const YAML::Node& map, const std::string& file, const std::string& what)
      : YamlFields(map, YamlSource{file, {}}, what) {}

  // Where `node` is; a key this map lacks is placed at the map itself.
  std::string where(const YAML::Node& node) const;
  std::string where() const { return where(map_); }
  const YamlSource& source() const { return source_; }

  bool has(const char* key) const { return static_cast<bool>(node(key)); }
  // Absent (false) when the key or the whole map is (a default-built
  // YAML::Node would be a present null).
  YAML::Node node(const char* key) const { return map_ ? map_[key] : map_; }

  // Fails "unknown key 'k' (expected one of: a, b)" at the first other key.
  void allow_only(std::initializer_list<const char*> keys) const;

  // The field as a T; `fallback` when absent; "bad value for 'k'" when it is
  // not a T.
  template <typename T>
  T get(const char* key, const T& fallback) const {
    const YAML::Node n = node(key);
    if (!n) return fallback;
    return yaml_value<T>(n, key, source_);
  }
  std::string str(const char* key, const std::string& fallback = "") const {
    return get<std::string>(key, fallback);
  }
  // true or false: "bad value for 'k' (true or false)".
  bool flag(const char* key, bool fallback) const;
  // A finite number in [lo, hi]: "'k' = v is out of range [lo, hi]". A
  // double unless T is named (the fallback does not choose it).
  template <typename T = double>
  T number(const char* key, std::common_type_t<T> fallback, double lo, double hi) const {
    const T value = get<T>(key, fallback);
    check_range(key, static_cast<double>(value), lo, hi);
    return value;
  }
  // [x, y] and [x, y, z] of finite numbers: "'k' must be [x, y]".
  Eigen::Vector2d vec2(const char* key, const Eigen::Vector2d& fallback) const;
  Eigen::Vector3d vec3(const char* key, const Eigen::Vector3d& fallback) const;

 private:
  void check_range(const char* key, double value, double lo, double hi) const;

  YAML::Node map_;
  YamlSource source_;
};

}  // namespace depot
