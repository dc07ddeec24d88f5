#pragma once
// Where the shipped scenarios live, and resolving a scenario argument.
#include <string>

namespace depot::sim {

// $DEPOT_SCENARIOS, else the project's scenarios/ folder (common/config_path.h).
std::string scenarios_folder();
// A path to a YAML file, or the name of a shipped scenario.
std::string resolve_scenario(const std::string& name_or_path);

}  // namespace depot::sim
