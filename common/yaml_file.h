#pragma once
// Loading a YAML file with the project's one-line error messages.
#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

namespace depot {

// Parses the YAML file at `path`. Throws Error("<path>: cannot open <what>")
// when the file cannot be read and
// Error("<path>:<line>: YAML syntax error: <msg>") when it does not parse.
YAML::Node load_yaml_file(const std::string& path, const std::string& what);

// `text` from a file as an error message may quote it: one line, control
// characters escaped ("\n", "\x01").
std::string printable(const std::string& text);

// "<path>:<line>" of a node of the file at `path`, for error messages.
std::string yaml_where(const std::string& path, const YAML::Node& node);

// Throws Error("<path>:<line>: unknown key 'k' (expected a, b, c)") for the
// first key of the map `node` that is not in `known`.
void check_known_keys(const YAML::Node& node, const std::vector<std::string>& known,
                      const std::string& path);

}  // namespace depot
