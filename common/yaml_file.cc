#include "common/yaml_file.h"

#include "common/error.h"

namespace depot {

YAML::Node load_yaml_file(const std::string& path, const std::string& what) {
  try {
    return YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    fail(path, "cannot open " + what);
  } catch (const YAML::Exception& e) {
    fail(path + ":" + std::to_string(e.mark.line + 1), "YAML syntax error: " + e.msg);
  }
}

}  // namespace depot
