#pragma once
// Command-line options shared by the commands that build a detector
// (`slam run`, `eval detector`, `eval calibrate`).
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "common/yaml_overrides.h"

namespace depot::cli {

// --detector-set KEY=VALUE (repeatable), parsed into `overrides`; `help`
// says what it changes for this command. `overrides` must outlive `cmd`'s
// parsing.
void add_detector_set_option(CLI::App* cmd, std::vector<YamlOverride>& overrides,
                             const std::string& help);

}  // namespace depot::cli
