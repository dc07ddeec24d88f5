#pragma once
// Reading the fields of the small model YAML files (detectors, segmenters)
// with one-line errors "<file>:<line>: <problem>".
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <string>

#include "common/error.h"
#include "common/yaml_file.h"

namespace depot::slam {

// The folder of a file path ("." for a bare name).
std::string folder_of(const std::string& path);

// root[key] as a string; "" when absent. Throws when it is not a scalar.
std::string read_string(const YAML::Node& root, const char* key, const std::string& path);

// root[key] as a T in [lo, hi]; `fallback` when absent.
template <typename T>
T read_number(const YAML::Node& root, const char* key, T fallback, double lo, double hi,
              const std::string& path) {
  const YAML::Node n = root[key];
  if (!n) return fallback;
  T v;
  try {
    v = n.as<T>();
  } catch (const YAML::Exception&) {
    fail(yaml_where(path, n), std::string("bad value for '") + key + "'");
  }
  const double d = static_cast<double>(v);
  if (!std::isfinite(d) || d < lo || d > hi)
    fail(yaml_where(path, n), std::string("'") + key + "' must be in [" + std::to_string(lo) +
                                  ", " + std::to_string(hi) + "]");
  return v;
}

}  // namespace depot::slam
