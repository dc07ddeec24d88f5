#include "tools/depot/sweep_file.h"

#include <yaml-cpp/yaml.h>

#include <filesystem>

#include "common/error.h"
#include "common/image_size.h"
#include "common/yaml_fields.h"
#include "common/yaml_file.h"

namespace fs = std::filesystem;

namespace depot::cli {
namespace {

// A scalar or a list of scalars, as the command line writes levels.
std::string levels_of(const YamlFields& f, const YAML::Node& value, const std::string& name) {
  std::vector<std::string> levels;
  try {
    if (value.IsSequence())
      levels = value.as<std::vector<std::string>>();
    else if (value.IsScalar())
      levels = {value.as<std::string>()};
  } catch (const YAML::Exception&) {
    levels.clear();
  }
  if (levels.empty()) fail(f.where(value), "'" + name + "' must be a value or a list of values");
  std::string text = name + "=";
  for (size_t i = 0; i < levels.size(); ++i) text += (i ? "," : "") + levels[i];
  return text;
}

std::vector<std::string> parameters(const YamlFields& top, const char* key, bool one_value) {
  std::vector<std::string> out;
  const YAML::Node map = top.node(key);
  if (!map) return out;
  if (!map.IsMap()) fail(top.where(map), "'" + std::string(key) + "' must be a map PARAM: levels");
  for (const auto& kv : map) {
    const std::string name = kv.first.as<std::string>();
    if (one_value && !kv.second.IsScalar())
      fail(top.where(kv.second), "'" + std::string(key) + "." + name + "' takes one value");
    out.push_back(levels_of(top, kv.second, name));
  }
  return out;
}

}  // namespace

SweepFile read_sweep_file(const std::string& path) {
  const YAML::Node root = load_yaml_file(path, "sweep file");
  const YamlFields top(root, path, "sweep file");
  top.allow_only(
      {"description", "scenarios", "vary", "set", "modes", "seeds", "frames", "width", "mapping"});
  SweepFile s;
  s.description = top.str("description");
  const fs::path folder = fs::path(path).parent_path();
  for (const std::string& name : top.get<std::vector<std::string>>("scenarios", {})) {
    // A file is found beside the sweep file; a bare name is a shipped scenario.
    const bool file = fs::path(name).extension() == ".yaml" || name.find('/') != std::string::npos;
    s.scenarios.push_back(file && fs::path(name).is_relative() ? (folder / name).string() : name);
  }
  if (s.scenarios.empty()) fail(top.where(top.node("scenarios")), "'scenarios' lists none");
  s.vary = parameters(top, "vary", false);
  s.fixed = parameters(top, "set", true);
  if (top.has("modes")) s.modes = top.get<std::vector<std::string>>("modes", {});
  if (top.has("seeds")) s.seeds = top.number<int>("seeds", 3, 1, 1000);
  if (top.has("frames")) s.frames = top.number<int>("frames", 300, 10, 100000);
  if (top.has("width")) s.width = top.number<int>("width", 640, kMinImageSide, kMaxImageSide);
  if (top.has("mapping")) {
    s.mapping = top.str("mapping");
    if (*s.mapping != "sync" && *s.mapping != "threaded")
      fail(top.where(top.node("mapping")), "mapping must be sync or threaded");
  }
  return s;
}

}  // namespace depot::cli
