#pragma once
// Loading a YAML file with the project's one-line error messages.
#include <yaml-cpp/yaml.h>

#include <string>

namespace depot {

// Parses the YAML file at `path`. Throws Error("<path>: cannot open <what>")
// when the file cannot be read and
// Error("<path>:<line>: YAML syntax error: <msg>") when it does not parse.
YAML::Node load_yaml_file(const std::string& path, const std::string& what);

}  // namespace depot
