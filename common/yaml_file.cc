#include "common/yaml_file.h"

#include <fmt/format.h>

#include <algorithm>

#include "common/error.h"

namespace depot {

std::string printable(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      out += fmt::format("\\x{:02x}", static_cast<unsigned char>(c));
    } else {
      out += c;
    }
  }
  return out;
}

YAML::Node load_yaml_file(const std::string& path, const std::string& what) {
  try {
    return YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    fail(path, "cannot open " + what);
  } catch (const YAML::Exception& e) {
    // yaml-cpp quotes the offending character, which may be a newline.
    fail(path + ":" + std::to_string(e.mark.line + 1), "YAML syntax error: " + printable(e.msg));
  }
}

std::string yaml_where(const std::string& path, const YAML::Node& node) {
  return path + ":" + std::to_string(node.Mark().line + 1);
}

void check_known_keys(const YAML::Node& node, const std::vector<std::string>& known,
                      const std::string& path) {
  for (const auto& kv : node) {
    const std::string key = kv.first.Scalar();
    if (std::find(known.begin(), known.end(), key) != known.end()) continue;
    std::string list;
    for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
    fail(yaml_where(path, kv.first),
         "unknown key '" + printable(key) + "' (expected " + list + ")");
  }
}

}  // namespace depot
