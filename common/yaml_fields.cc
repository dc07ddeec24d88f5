#include "common/yaml_fields.h"

#include <algorithm>
#include <set>

#include "common/yaml_file.h"

namespace depot {

std::string YamlSource::where(const YAML::Node& node) const {
  for (const auto& [value, option] : overrides)
    if (value.is(node)) return option;
  if (node.Mark().is_null()) return file;
  return file + ":" + std::to_string(node.Mark().line + 1);
}

YamlFields::YamlFields(const YAML::Node& map, YamlSource source, const std::string& what)
    : map_(map), source_(std::move(source)) {
  if (map_ && !map_.IsMap()) fail(where(map_), what + " must be a map");
}

std::string YamlFields::where(const YAML::Node& node) const {
  if (node) return source_.where(node);
  return map_ ? source_.where(map_) : source_.file;
}

void YamlFields::allow_only(std::initializer_list<const char*> keys) const {
  if (!map_) return;
  const std::set<std::string> known(keys.begin(), keys.end());
  for (const auto& kv : map_) {
    if (!kv.first.IsScalar()) fail(where(kv.first), "a key must be a plain name");
    const std::string key = kv.first.Scalar();
    if (known.count(key)) continue;
    std::string list;
    for (const char* k : keys) list += std::string(list.empty() ? "" : ", ") + k;
    fail(where(kv.first), "unknown key '" + printable(key) + "' (expected one of: " + list + ")");
  }
}

bool YamlFields::flag(const char* key, bool fallback) const {
  const YAML::Node n = node(key);
  if (!n) return fallback;
  try {
    return n.as<bool>();
  } catch (const YAML::Exception&) {
    fail(where(n), "bad value for '" + std::string(key) + "' (true or false)");
  }
}

void YamlFields::check_range(const char* key, double value, double lo, double hi) const {
  if (std::isfinite(value) && value >= lo && value <= hi) return;
  fail(where(node(key)), "'" + std::string(key) + "' = " + shortest_number(value) +
                             " is out of range [" + shortest_number(lo) + ", " +
                             shortest_number(hi) + "]");
}

namespace {

template <int N>
Eigen::Matrix<double, N, 1> fixed_vector(const YamlFields& f, const char* key,
                                         const Eigen::Matrix<double, N, 1>& fallback,
                                         const char* shape) {
  const YAML::Node n = f.node(key);
  if (!n) return fallback;
  const std::vector<double> v = f.get<std::vector<double>>(key, {});
  if (v.size() != static_cast<size_t>(N) ||
      !std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); }))
    fail(f.where(n), "'" + std::string(key) + "' must be " + shape);
  Eigen::Matrix<double, N, 1> out;
  for (int i = 0; i < N; ++i) out[i] = v[static_cast<size_t>(i)];
  return out;
}

}  // namespace

Eigen::Vector2d YamlFields::vec2(const char* key, const Eigen::Vector2d& fallback) const {
  return fixed_vector<2>(*this, key, fallback, "[x, y]");
}

Eigen::Vector3d YamlFields::vec3(const char* key, const Eigen::Vector3d& fallback) const {
  return fixed_vector<3>(*this, key, fallback, "[x, y, z]");
}

}  // namespace depot
