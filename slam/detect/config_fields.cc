#include "slam/detect/config_fields.h"

namespace depot::slam {

std::string folder_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
}

std::string read_string(const YAML::Node& root, const char* key, const std::string& path) {
  const YAML::Node n = root[key];
  if (!n) return {};
  if (!n.IsScalar()) fail(yaml_where(path, n), std::string("'") + key + "' must be a string");
  return n.as<std::string>();
}

}  // namespace depot::slam
