#include "common/yaml_overrides.h"

#include "common/error.h"

namespace depot {
namespace {

std::vector<std::string> split_key(const std::string& key, const std::string& where) {
  std::vector<std::string> parts;
  size_t start = 0;
  while (true) {
    const size_t dot = key.find('.', start);
    const std::string part = key.substr(start, dot == std::string::npos ? dot : dot - start);
    if (part.empty()) fail(where, "bad setting name '" + key + "' (empty part)");
    parts.push_back(part);
    if (dot == std::string::npos) return parts;
    start = dot + 1;
  }
}

}  // namespace

YamlOverride parse_yaml_override(const std::string& text, const std::string& where) {
  const size_t eq = text.find('=');
  if (eq == std::string::npos) fail(where, "expected KEY=VALUE, got '" + text + "'");
  YamlOverride o{text.substr(0, eq), text.substr(eq + 1)};
  if (o.key.empty()) fail(where, "missing key in '" + text + "'");
  if (o.value.empty()) fail(where, "missing value in '" + text + "'");
  split_key(o.key, where);
  return o;
}

void apply_yaml_override(YAML::Node& root, const YamlOverride& override_,
                         const std::string& where) {
  const std::vector<std::string> parts = split_key(override_.key, where);
  YAML::Node value;
  try {
    value = YAML::Load(override_.value);
  } catch (const YAML::Exception& e) {
    fail(where, "value of '" + override_.key + "' is not valid YAML: " + e.msg);
  }
  if (!root || root.IsNull()) root = YAML::Node(YAML::NodeType::Map);
  if (!root.IsMap()) fail(where, "cannot set '" + override_.key + "': the file is not a map");
  YAML::Node node;
  node.reset(root);
  for (size_t i = 0; i + 1 < parts.size(); ++i) {
    YAML::Node child = node[parts[i]];
    if (!child || child.IsNull()) {
      node[parts[i]] = YAML::Node(YAML::NodeType::Map);
      child = node[parts[i]];
    }
    if (!child.IsMap())
      fail(where, "cannot set '" + override_.key + "': '" + parts[i] + "' is not a map");
    node.reset(child);
  }
  node[parts.back()] = value;
}

YAML::Node overrides_to_node(const std::vector<YamlOverride>& overrides, const std::string& where) {
  YAML::Node root(YAML::NodeType::Map);
  for (const auto& o : overrides) apply_yaml_override(root, o, where);
  return root;
}

}  // namespace depot
